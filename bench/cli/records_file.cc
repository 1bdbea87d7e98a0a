#include "bench/cli/records_file.h"

#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench/cli/io.h"

namespace ocpb {

namespace fs = std::filesystem;
using nlohmann::json;

RecordFile ReadRecords(const std::string& path) {
  RecordFile file;
  if (!fs::exists(path)) return file;
  const std::string text = ReadFile(path);
  file.unterminated = !text.empty() && text.back() != '\n';
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty()) lines.push_back(line);
  }
  for (size_t i = 0; i < lines.size(); ++i) {
    json j;
    try {
      j = json::parse(lines[i]);
    } catch (const json::exception&) {  // parse_error, or out_of_range (1e999)
    }
    if (!j.is_object()) {
      if (i + 1 == lines.size()) {
        file.dropped_partial = true;
        continue;
      }
      throw std::invalid_argument(fmt::format("{}: line {} is not a JSON record", path, i + 1));
    }
    try {
      file.records.push_back(Record::FromJson(j));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("{}: line {}: {}", path, i + 1, e.what()));
    }
    file.lines.push_back(lines[i]);
  }
  return file;
}

std::string JoinLines(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& l : lines) text += l + "\n";
  return text;
}

}  // namespace ocpb
