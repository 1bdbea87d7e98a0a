# Warnings as errors on OCPBench's own code (never on third-party headers, which are SYSTEM).
function(ocpb_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror)
endfunction()

# With OCPB_FUZZ, libFuzzer's coverage instrumentation (-fsanitize=fuzzer-no-link) on the code the
# fuzz targets explore: the parsers of suites, records, initial guesses and measurement files, and
# the option schemas they validate against (ocpb_core, ocpb_channel, ocpb_cli, the fuzz entries).
# Not on the numerical libraries nor on the tests: the fuzzers' inputs do not reach that code,
# and its comparison callbacks cost a tenth of those objects' compile time and slow every test.
function(ocpb_fuzz_coverage target)
  if(OCPB_FUZZ)
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
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

# ocpb_test(name SOURCES ... DEPS ... [PROPERTIES ...] [UNOPTIMIZED]): a GoogleTest binary
# registered with CTest, each test with the given CTest properties (for example an ENVIRONMENT or
# a fixture). UNOPTIMIZED: in a Debug build (the sanitizer preset, -O1 elsewhere) the test files
# are compiled at -O0. For binaries whose tests drive programs, parse and compare rather than
# compute (the libraries they call stay at -O1): measured on cli_test, transcriptions_test,
# core_test and online_replanning_test together, about 145 s less compile CPU and the same test
# time (60 s); solvers_test, problems_test and channel_test compute in their own files and ran
# 1.3-3.2x longer at -O0, more than they save (README, Build times).
function(ocpb_test name)
  cmake_parse_arguments(ARG "UNOPTIMIZED" "" "SOURCES;DEPS;PROPERTIES" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest_main)
  ocpb_set_warnings(${name})
  if(ARG_UNOPTIMIZED)
    target_compile_options(${name} PRIVATE $<$<CONFIG:Debug>:-O0>)
  endif()
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600 ${ARG_PROPERTIES})
endfunction()
