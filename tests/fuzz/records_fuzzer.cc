// libFuzzer target: the records loader (`run --resume`, the shard files `merge` reads) must turn
// any input into either records or a std::invalid_argument naming the line, never a crash, a
// hang or another exception; every record it accepts writes and reads back.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

#include <nlohmann/json.hpp>

#include "bench/cli/records_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  ocpb::RecordFile file;
  try {
    file = ocpb::ParseRecords(text, "fuzz");
  } catch (const std::invalid_argument&) {
    return 0;
  }
  if (file.records.size() != file.lines.size() || file.records.size() != file.line_numbers.size()) {
    std::abort();
  }
  for (const ocpb::Record& r : file.records) {
    // What was read is a record this build writes, and reads back.
    const std::string line = r.ToJson().dump();
    (void)ocpb::Record::FromJson(nlohmann::json::parse(line));
  }
  file.DropDuplicateKeys();
  return 0;
}
