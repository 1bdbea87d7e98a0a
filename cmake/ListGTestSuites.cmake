# cmake -D EXECUTABLE=<GoogleTest binary> -D OUTPUT=<file> -P ListGTestSuites.cmake
# Writes `set(ocpb_gtest_suites ...)`, the binary's test suites in its own order, to OUTPUT (read by
# ocpb_add_gtest_suites' include file, GTestSuites.cmake). Fails the build when the binary cannot
# list its tests or lists none.
execute_process(COMMAND ${EXECUTABLE} --gtest_list_tests
                OUTPUT_VARIABLE listing ERROR_VARIABLE errors RESULT_VARIABLE rc TIMEOUT 60)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${EXECUTABLE} --gtest_list_tests failed (${rc}):\n${errors}")
endif()
# A suite line starts in column 0 and ends its name with a dot (a typed suite's comment follows);
# the tests below it are indented; gtest_main's "Running main() ..." line has no such name.
string(REGEX MATCHALL "(^|\n)[A-Za-z_][A-Za-z0-9_/]*\\." lines "${listing}")
set(content "set(ocpb_gtest_suites")
set(count 0)
foreach(line IN LISTS lines)
  string(REGEX REPLACE "^\n?(.*)\\.$" "\\1" suite "${line}")
  string(APPEND content "\n  [==[${suite}]==]")
  math(EXPR count "${count} + 1")
endforeach()
if(count EQUAL 0)
  message(FATAL_ERROR "${EXECUTABLE} lists no test suite")
endif()
file(WRITE ${OUTPUT} "${content})\n")
