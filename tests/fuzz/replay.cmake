# Ordinary-build replay of the fuzzers' corpora and regressions (see replay_main.cc).
set(FUZZ_DIR ${PROJECT_SOURCE_DIR}/tests/fuzz)
add_executable(measurement_fuzz_replay ${FUZZ_DIR}/replay_main.cc ${FUZZ_DIR}/measurement_fuzzer.cc
               ${PROJECT_SOURCE_DIR}/problems/channel/measurement_file.cc)
target_include_directories(measurement_fuzz_replay PRIVATE ${PROJECT_SOURCE_DIR})
target_link_libraries(measurement_fuzz_replay PRIVATE Eigen3::Eigen)
foreach(target suite records initial_guess)
  add_executable(${target}_fuzz_replay ${FUZZ_DIR}/replay_main.cc ${FUZZ_DIR}/${target}_fuzzer.cc)
  target_link_libraries(${target}_fuzz_replay PRIVATE ocpb_cli)
endforeach()
foreach(target measurement suite records initial_guess)
  ocpb_set_warnings(${target}_fuzz_replay)
  set_target_properties(${target}_fuzz_replay PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
  add_test(NAME fuzz_replay.${target}
           COMMAND ${target}_fuzz_replay ${FUZZ_DIR}/corpus/${target} ${FUZZ_DIR}/regressions/${target})
endforeach()
