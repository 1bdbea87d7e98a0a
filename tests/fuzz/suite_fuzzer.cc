// libFuzzer target: the suite-file parser must turn any input into either a suite or a
// std::invalid_argument, never a crash, a hang or another exception.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "bench/cli/suite.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {  // parse_error, out_of_range (1e999), ...
    return 0;
  }
  try {
    ocpb::ParseSuite(j, "fuzz");
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
