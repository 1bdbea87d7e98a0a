# ocpb_add_gtest_suites(target [PROPERTIES ...]): one CTest test per GoogleTest suite of the test
# binary `target`, named `<target>.<suite>` (two binaries may have suites of the same name) and
# running `target --gtest_filter=<suite>.*`, each with the given CTest properties and a 600 s
# timeout.
#
# Why suites and not single tests (CMake's gtest_discover_tests): every test process of the
# sanitizer build pays a fixed start and exit (ASan's shadow memory, the binary's pages, the leak
# check): transcriptions_test's 242 tests took 49.7 s of CPU as 242 processes and 36.5 s as one
# (2026-12-03). A suite keeps one concept's tests together: a failure still names its test (the
# output lists each), `ctest -R '\.<suite>$'` runs a concept and `ctest -R '^solvers_test\.'` a
# binary. A suite that runs no test fails (a filter that matches nothing would pass vacuously).
# PROPERTIES are name/value pairs as for set_tests_properties; a value that holds a `;` (a list)
# is not supported (it would be split into pairs).
#
# After each build of `target` its suites are listed (`--gtest_list_tests`) into
# <target>_suites.cmake; CTest reads the list through a file registered in TEST_INCLUDE_FILES.
set(OCPB_LIST_GTEST_SUITES_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/ListGTestSuites.cmake)

function(ocpb_add_gtest_suites target)
  cmake_parse_arguments(ARG "" "" "PROPERTIES" ${ARGN})
  set(list_file ${CMAKE_CURRENT_BINARY_DIR}/${target}_suites.cmake)
  add_custom_command(
    TARGET ${target} POST_BUILD
    BYPRODUCTS ${list_file}
    COMMAND ${CMAKE_COMMAND} -D EXECUTABLE=$<TARGET_FILE:${target}> -D OUTPUT=${list_file}
            -P ${OCPB_LIST_GTEST_SUITES_SCRIPT}
    VERBATIM)
  # The properties are written here, at configure time, as bracket arguments (an ENVIRONMENT
  # value may hold any character); the build only writes the suites' names.
  set(properties "TIMEOUT 600 FAIL_REGULAR_EXPRESSION [==[\\[==========\\] 0 tests from]==]")
  foreach(value IN LISTS ARG_PROPERTIES)
    string(APPEND properties " [==[${value}]==]")
  endforeach()
  file(GENERATE OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/${target}_suites_include.cmake CONTENT "\
if(EXISTS [==[${list_file}]==])
  include([==[${list_file}]==])
  foreach(suite IN LISTS ocpb_gtest_suites)
    add_test(\"${target}.\${suite}\" [==[$<TARGET_FILE:${target}>]==] \"--gtest_filter=\${suite}.*\")
    set_tests_properties(\"${target}.\${suite}\" PROPERTIES ${properties})
  endforeach()
else()
  add_test(${target}_NOT_BUILT ${target}_NOT_BUILT)
endif()
")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES
                                         ${CMAKE_CURRENT_BINARY_DIR}/${target}_suites_include.cmake)
endfunction()
