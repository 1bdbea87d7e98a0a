# The libFuzzer targets: OCPB_FUZZ_TARGETS is their one list. A target <name> is the entry point
# LLVMFuzzerTestOneInput in <name>_fuzzer.cc with its seed corpus in corpus/<name>/ (and the
# crashes it once found in regressions/<name>/). Each entry is compiled once and linked twice:
# into the libFuzzer executable <name>_fuzzer (CMakeLists.txt here, OCPB_FUZZ) and into the test
# fuzz_replay.<name> (replay.cmake), which replays the corpus and regressions in every test run.
# .ci/fuzz fuzzes every target of this list unless FUZZ_TARGETS names some.
# The list and its folder are set on every include: tests/ (the replay tests) and tests/fuzz/ (the
# fuzzers, added from the top level) are sibling scopes, and the guard below skips the rest of
# this file the second time, so a variable set after it would be empty in the second scope.
set(OCPB_FUZZ_DIR ${PROJECT_SOURCE_DIR}/tests/fuzz)
set(OCPB_FUZZ_TARGETS measurement suite records initial_guess compare)
include_guard(GLOBAL)
foreach(target IN LISTS OCPB_FUZZ_TARGETS)
  add_library(${target}_fuzz_entry OBJECT ${OCPB_FUZZ_DIR}/${target}_fuzzer.cc)
  # All of OCPBench (ocpb_cli and what it links): one link line for every entry.
  target_link_libraries(${target}_fuzz_entry PUBLIC ocpb_cli)
  ocpb_set_warnings(${target}_fuzz_entry)
  ocpb_fuzz_coverage(${target}_fuzz_entry)
  # An entry hands bytes to a parser of the libraries: -O0 in the sanitizer build, like the
  # tests' files (26 s of compile CPU at -O1 for the five, measured 2026-12-07); its executables
  # link the libraries first (ocpb_link_libraries_first, fuzz/CMakeLists.txt and replay.cmake).
  ocpb_unoptimized_in_debug(${target}_fuzz_entry)
endforeach()
