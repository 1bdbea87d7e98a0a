# Ordinary-build replay of the fuzzers' corpora and regressions (see replay_main.cc).
include(${PROJECT_SOURCE_DIR}/tests/fuzz/entries.cmake)
foreach(target IN LISTS OCPB_FUZZ_TARGETS)
  add_executable(${target}_fuzz_replay ${OCPB_FUZZ_DIR}/replay_main.cc)
  target_link_libraries(${target}_fuzz_replay PRIVATE ${target}_fuzz_entry)
  ocpb_link_libraries_first(${target}_fuzz_replay ocpb_cli)
  ocpb_set_warnings(${target}_fuzz_replay)
  set_target_properties(${target}_fuzz_replay PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
  add_test(NAME fuzz_replay.${target}
           COMMAND ${target}_fuzz_replay ${OCPB_FUZZ_DIR}/corpus/${target} ${OCPB_FUZZ_DIR}/regressions/${target})
endforeach()
