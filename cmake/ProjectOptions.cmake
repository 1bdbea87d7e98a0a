# Warnings on OCPBench's own code (never on third-party headers, which are SYSTEM); errors only
# where OCPB_WARNINGS_AS_ERRORS asks for them (the presets and CI), so that a user's build with
# another compiler version is not stopped by a warning that compiler adds.
function(ocpb_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  # GCC 12 (Debian 12's) at -O2/-O3 in C++20 reports a -Wrestrict inside libstdc++'s std::string
  # for `"text" + std::string(...)` (an overlap of 2^63 bytes that cannot happen; a known false
  # report fixed in GCC 13). It stopped a GCC Release build four times, in code and tests that
  # clang and GCC at -O0 build cleanly, each time at a new site; OCPBench has no restrict pointers
  # of its own for the warning to guard.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  if(OCPB_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# With OCPB_FUZZ, libFuzzer's coverage instrumentation on the libraries the fuzz targets run.
# ocpb_fuzz_coverage(target): all of it (-fsanitize=fuzzer-no-link: edge counters, indirect calls
# and the comparison callbacks that guide mutations towards the values a parser tests), for the
# parsers of suites, records, initial guesses and measurement files and the option schemas
# (ocpb_core, ocpb_channel, ocpb_cli, the fuzz entries). ocpb_fuzz_edges(target): edge counters
# only, for the problem, solver, transcription and online libraries, whose registries, option
# checks and problem constructors the suite fuzzer also runs: with the comparison callbacks in
# their numerical loops, tests that run them took 1.5-1.75x the CPU; the counters alone cost the
# whole test run 2 % (ctest 163 -> 167 s). Not on the tests (the fuzzers do not run them).
function(ocpb_fuzz_coverage target)
  if(OCPB_FUZZ)
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()
function(ocpb_fuzz_edges target)
  if(OCPB_FUZZ)
    target_compile_options(${target} PRIVATE -fsanitize-coverage=inline-8bit-counters,pc-table)
  endif()
endfunction()

# ocpb_library(name SOURCES ... DEPS ...): a static library of project code.
function(ocpb_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
  target_compile_features(${name} PUBLIC cxx_std_20)
  ocpb_set_warnings(${name})
endfunction()

# ocpb_unoptimized_in_debug(target): in a Debug build (the sanitizer preset, -O1 elsewhere) the
# target's own files compile at -O0. For code that drives programs, parses and compares rather
# than computes: with the sanitizers, clang's -O1 takes about 2.8x the CPU of -O0 on such files
# (solvers_test's unity file, measured 2026-12-06: 167 s against 59 s), while the run time is the
# libraries' (which stay at -O1). An inline or template function that both compile may be linked
# as the -O0 copy.
function(ocpb_unoptimized_in_debug target)
  target_compile_options(${target} PRIVATE $<$<CONFIG:Debug>:-O0>)
endfunction()

# ocpb_test(name SOURCES ... DEPS ... [PROPERTIES ...] [UNOPTIMIZED]): a GoogleTest binary
# registered with CTest one test per GoogleTest suite (ocpb_add_gtest_suites, GTestSuites.cmake),
# each with the given CTest properties (for example an ENVIRONMENT or a fixture). UNOPTIMIZED:
# ocpb_unoptimized_in_debug, for binaries whose tests drive programs, parse and compare: measured
# on cli_test, transcriptions_test, core_test and online_replanning_test together, about 145 s
# less compile CPU and the same test time (60 s); solvers_test, problems_test and channel_test
# compute in their own files and ran 1.3-3.2x longer at -O0, more than they save.
function(ocpb_test name)
  cmake_parse_arguments(ARG "UNOPTIMIZED" "" "SOURCES;DEPS;PROPERTIES" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest_main)
  ocpb_set_warnings(${name})
  if(ARG_UNOPTIMIZED)
    ocpb_unoptimized_in_debug(${name})
  endif()
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
  ocpb_add_gtest_suites(${name} PROPERTIES ${ARG_PROPERTIES})
endfunction()
