// libFuzzer target: the suite-file reader must turn any input into either a suite or a
// std::invalid_argument, never a crash, a hang or another exception. The text goes the way
// LoadSuite takes it: ParseJsonText (nesting limit, errors with lines), JsonLines, ParseSuite.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include <nlohmann/json.hpp>

#include "bench/cli/json_input.h"
#include "bench/cli/suite.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const nlohmann::json j = ocpb::ParseJsonText(text, "fuzz");
    const ocpb::JsonLines lines(text, j);
    ocpb::ParseSuite(j, "fuzz", &lines);
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
