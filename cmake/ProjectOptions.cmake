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
# as the -O0 copy: a library marked so is linked after the fully optimized ones
# (ocpb_link_libraries_first).
function(ocpb_unoptimized_in_debug target)
  target_compile_options(${target} PRIVATE $<$<CONFIG:Debug>:-O0>)
  set_property(TARGET ${target} PROPERTY OCPB_UNOPTIMIZED_CODE ON)
endfunction()

# ocpb_unoptimized_sources_in_debug(target file...): the same for single files of a library
# whose run time the tests do not feel (option binding, a kernel only its own short tests run)
# while their -O1 compile is long. A file with its own compile options leaves the library's
# unity file and compiles alone (after it in the archive, so the library's -O1 copies of shared
# inline code come first in a link; the library itself is linked after the fully optimized
# ones). Only where a Debug build can be configured, so that other builds keep their unity files
# whole.
function(ocpb_unoptimized_sources_in_debug target)
  get_property(multi_config GLOBAL PROPERTY GENERATOR_IS_MULTI_CONFIG)
  string(TOLOWER "${CMAKE_BUILD_TYPE}" build_type)
  if(multi_config OR build_type STREQUAL "debug")
    set_source_files_properties(${ARGN} PROPERTIES COMPILE_OPTIONS $<$<CONFIG:Debug>:-O0>)
    set_property(TARGET ${target} PROPERTY OCPB_UNOPTIMIZED_CODE ON)
  endif()
endfunction()

# ocpb_project_libraries(out target...): the OCPBench static libraries the targets link,
# directly or through other OCPBench libraries (public dependencies), each after the libraries it
# depends on, and those with -O0 code in a Debug build (OCPB_UNOPTIMIZED_CODE) after all others.
function(ocpb_project_libraries out)
  set(found)
  set(queue ${ARGN})
  while(queue)
    list(POP_FRONT queue item)
    if(NOT item MATCHES "^ocpb_" OR NOT TARGET ${item} OR item IN_LIST found)
      continue()
    endif()
    get_target_property(kind ${item} TYPE)
    if(NOT kind STREQUAL "STATIC_LIBRARY")
      continue()
    endif()
    list(APPEND found ${item})
    get_target_property(deps ${item} INTERFACE_LINK_LIBRARIES)
    if(deps)
      list(APPEND queue ${deps})
    endif()
  endwhile()
  # Dependencies first: take, round by round, the libraries none of whose dependencies is left.
  set(remaining ${found})
  set(ordered)
  while(remaining)
    set(ready)
    foreach(lib IN LISTS remaining)
      get_target_property(deps ${lib} INTERFACE_LINK_LIBRARIES)
      set(waits FALSE)
      foreach(dep IN LISTS deps)
        if(dep IN_LIST remaining)
          set(waits TRUE)
        endif()
      endforeach()
      if(NOT waits)
        list(APPEND ready ${lib})
      endif()
    endforeach()
    if(NOT ready)
      message(FATAL_ERROR "ocpb_project_libraries: a dependency cycle among ${remaining}")
    endif()
    list(APPEND ordered ${ready})
    list(REMOVE_ITEM remaining ${ready})
  endwhile()
  set(optimized)
  set(unoptimized)
  foreach(lib IN LISTS ordered)
    get_target_property(has_o0 ${lib} OCPB_UNOPTIMIZED_CODE)
    if(has_o0)
      list(APPEND unoptimized ${lib})
    else()
      list(APPEND optimized ${lib})
    endif()
  endforeach()
  set(${out} ${optimized} ${unoptimized} PARENT_SCOPE)
endfunction()

# ocpb_link_libraries_first(target lib...): in a Debug build on Linux the linker reads every
# object of the OCPBench libraries `lib...` (and theirs, in the order of ocpb_project_libraries:
# the fully optimized ones first) before the target's own objects. An inline or template
# function that both compile (Eigen's kernels, the jets' arithmetic) is kept once, from the first
# object that has it: so an optimized copy serves the whole program, also where a test file or a
# library's -O0 file has its own (ocpb_unoptimized_in_debug, ocpb_unoptimized_sources_in_debug). Without this the test's -O0 copies won, and the libraries' loops
# ran them: solvers_test's AugmentedLagrangianLoop took over 4x its time when its files alone
# were at -O0 (measured 2026-12-06). Other builds compile everything alike and link as usual.
function(ocpb_link_libraries_first target)
  ocpb_project_libraries(libs ${ARGN})
  set(archives)
  foreach(lib IN LISTS libs)
    list(APPEND archives $<TARGET_FILE:${lib}>)
  endforeach()
  if(archives AND UNIX AND NOT APPLE)
    target_link_options(${target} PRIVATE
                        "$<$<CONFIG:Debug>:LINKER:--whole-archive;${archives};LINKER:--no-whole-archive>")
  endif()
endfunction()

# ocpb_test(name SOURCES ... DEPS ... [PROPERTIES ...]): a GoogleTest binary registered with
# CTest one test per GoogleTest suite (ocpb_add_gtest_suites, GTestSuites.cmake), each with the
# given CTest properties (for example an ENVIRONMENT or a fixture). The tests' own files compile
# at -O0 in a Debug build (ocpb_unoptimized_in_debug: the sanitizer preset), and the libraries'
# objects are linked first (ocpb_link_libraries_first), so that the code under test runs as the
# libraries compiled it (-O1) while the test files, which set up, drive and compare, cost about a
# third of their -O1 compile (solvers_test's unity file: 167 s at -O1, 59 s at -O0).
function(ocpb_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PROPERTIES" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest_main)
  ocpb_set_warnings(${name})
  ocpb_unoptimized_in_debug(${name})
  ocpb_link_libraries_first(${name} ${ARG_DEPS})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
  ocpb_add_gtest_suites(${name} PROPERTIES ${ARG_PROPERTIES})
endfunction()
