# Ordinary-build replay of the fuzzers' corpora and regressions (see replay_main.cc).
set(FUZZ_DIR ${PROJECT_SOURCE_DIR}/tests/fuzz)
add_executable(measurement_fuzz_replay ${FUZZ_DIR}/replay_main.cc ${FUZZ_DIR}/measurement_fuzzer.cc
               ${PROJECT_SOURCE_DIR}/problems/channel/measurement_file.cc)
target_include_directories(measurement_fuzz_replay PRIVATE ${PROJECT_SOURCE_DIR})
target_link_libraries(measurement_fuzz_replay PRIVATE Eigen3::Eigen)
add_executable(suite_fuzz_replay ${FUZZ_DIR}/replay_main.cc ${FUZZ_DIR}/suite_fuzzer.cc)
target_link_libraries(suite_fuzz_replay PRIVATE ocpb_cli)
foreach(target measurement suite)
  ocpb_set_warnings(${target}_fuzz_replay)
  set_target_properties(${target}_fuzz_replay PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
  add_test(NAME fuzz_replay.${target}
           COMMAND ${target}_fuzz_replay ${FUZZ_DIR}/corpus/${target} ${FUZZ_DIR}/regressions/${target})
endforeach()
