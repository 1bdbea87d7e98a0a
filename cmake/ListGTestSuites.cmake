# cmake -D EXECUTABLE=<GoogleTest binary> -D OUTPUT=<file> -P ListGTestSuites.cmake
# Writes `set(ocpb_gtest_suites ...)`, the binary's test suites in its own order, to OUTPUT (read by
# ocpb_add_gtest_suites' include file, GTestSuites.cmake). The old list is removed first, so a
# failed listing leaves no stale suites behind (CTest then reports the binary as not built). Fails
# the build when the binary cannot list its tests, lists none, or prints a line in column 0 that
# is not a suite's. Suites that would run no test (DISABLED_*) are left out.
file(REMOVE ${OUTPUT})
execute_process(COMMAND ${EXECUTABLE} --gtest_list_tests
                OUTPUT_VARIABLE listing ERROR_VARIABLE errors RESULT_VARIABLE rc TIMEOUT 60)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${EXECUTABLE} --gtest_list_tests failed (${rc}):\n${errors}")
endif()
# Only the names matter, so the characters that CMake's lists treat specially (a test's
# `# GetParam() = ...` comment may hold any) are replaced before the listing is split into lines.
string(REPLACE ";" "," listing "${listing}")
string(REPLACE "[" "(" listing "${listing}")
string(REPLACE "]" ")" listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")
set(content "set(ocpb_gtest_suites")
set(count 0)
# A suite is listed when it holds at least one test that runs: not a suite named DISABLED_*, nor
# one whose tests are all DISABLED_* (GoogleTest would run none of either, and a CTest test that
# runs no test fails by the "0 tests from" rule of GTestSuites.cmake).
set(suite "")
set(suite_runs OFF)
macro(ocpb_close_suite)
  if(suite_runs)
    string(APPEND content "\n  [==[${suite}]==]")
    math(EXPR count "${count} + 1")
  endif()
  set(suite_runs OFF)
endmacro()
foreach(line IN LISTS lines)
  if(line STREQUAL "" OR line MATCHES "^Running main\\(\\) from ")
    continue()  # gtest_main's greeting
  endif()
  if(line MATCHES "^  ([^ ]+)")
    # A test of the suite above (a parameterized test's `  # GetParam() = ...` follows its name).
    set(test "${CMAKE_MATCH_1}")  # before the next MATCHES resets CMAKE_MATCH_1
    if(NOT suite STREQUAL "" AND NOT suite MATCHES "^DISABLED_" AND NOT test MATCHES "^DISABLED_")
      set(suite_runs ON)
    endif()
    continue()
  endif()
  # A suite: its name and a dot in column 0 (a typed suite's `  # TypeParam = ...` follows).
  if(NOT line MATCHES "^([A-Za-z_][A-Za-z0-9_/]*)\\.(  #.*)?$")
    message(FATAL_ERROR "${EXECUTABLE} --gtest_list_tests: not a test suite: '${line}'")
  endif()
  ocpb_close_suite()
  set(suite "${CMAKE_MATCH_1}")
endforeach()
ocpb_close_suite()
if(count EQUAL 0)
  message(FATAL_ERROR "${EXECUTABLE} lists no test suite")
endif()
file(WRITE ${OUTPUT} "${content})\n")
