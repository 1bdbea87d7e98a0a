# The fuzz targets' entry points (LLVMFuzzerTestOneInput), compiled once and linked twice: into the
# libFuzzer executables (tests/fuzz/CMakeLists.txt, OCPB_FUZZ) and into the replay of their corpora
# in the test build (replay.cmake).
include_guard(GLOBAL)
set(OCPB_FUZZ_DIR ${PROJECT_SOURCE_DIR}/tests/fuzz)
add_library(measurement_fuzz_entry OBJECT ${OCPB_FUZZ_DIR}/measurement_fuzzer.cc)
target_link_libraries(measurement_fuzz_entry PUBLIC ocpb_channel)
add_library(suite_fuzz_entry OBJECT ${OCPB_FUZZ_DIR}/suite_fuzzer.cc)
target_link_libraries(suite_fuzz_entry PUBLIC ocpb_cli)
foreach(target measurement suite)
  ocpb_set_warnings(${target}_fuzz_entry)
endforeach()
