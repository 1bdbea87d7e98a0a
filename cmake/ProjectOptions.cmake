# Warnings as errors on OCPBench's own code (never on third-party headers, which are SYSTEM).
function(ocpb_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror)
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

# ocpb_test(name SOURCES ... DEPS ...): a GoogleTest binary registered with CTest.
function(ocpb_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest_main)
  ocpb_set_warnings(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)
endfunction()

# ocpb_unity_group(target group file...): with CMAKE_UNITY_BUILD (the presets turn it on), `target`
# is built from explicit unity groups instead of batches of 8 files. For targets whose files define
# same-named helpers in anonymous namespaces: such files go into different groups. A file in no
# group is compiled on its own, so a new file never breaks the build.
function(ocpb_unity_group target group)
  set_target_properties(${target} PROPERTIES UNITY_BUILD_MODE GROUP)
  set_source_files_properties(${ARGN} PROPERTIES UNITY_GROUP ${target}_${group})
endfunction()
