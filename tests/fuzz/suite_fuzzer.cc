// libFuzzer target: the suite-file reader must turn any input into either a suite or a
// std::invalid_argument, never a crash, a hang or another exception. The text goes the way
// LoadSuite takes it: ParseJsonText (nesting limit, errors with lines), JsonLines, ParseSuite.
// A document shaped as a sweep's shards.json (an object with a "suite" object) also has its
// suite read the way `merge` and `status` read it without --suite.
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
    if (j.is_object() && j.contains("suite") && j["suite"].is_object()) {
      try {
        ocpb::ParseSuite(j["suite"], "fuzz: suite");
      } catch (const std::invalid_argument&) {
      }
    }
    ocpb::ParseSuite(j, "fuzz", &lines);
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
