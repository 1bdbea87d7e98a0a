#include "bench/cli/records_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "bench/cli/json_input.h"
#include "core/memory_budget.h"

namespace ocpb {

using nlohmann::json;

int RecordFile::DropDuplicateKeys() {
  std::set<std::string> seen;
  size_t kept = 0;
  for (size_t i = 0; i < records.size(); ++i) {
    if (!records[i].key.empty() && !seen.insert(records[i].key).second) continue;
    if (kept != i) {
      records[kept] = std::move(records[i]);
      lines[kept] = std::move(lines[i]);
      line_numbers[kept] = line_numbers[i];
    }
    ++kept;
  }
  const int dropped = static_cast<int>(records.size() - kept);
  records.resize(kept);
  lines.resize(kept);
  line_numbers.resize(kept);
  return dropped;
}

RecordFile ParseRecords(std::string_view text, const std::string& source) {
  RecordFile file;
  file.unterminated = !text.empty() && text.back() != '\n';
  // Each non-empty line with its number in the file.
  std::vector<std::pair<std::string_view, int>> lines;
  int number = 0;
  while (!text.empty()) {
    const size_t nl = text.find('\n');
    const std::string_view line = text.substr(0, nl);
    text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
    ++number;
    if (!line.empty()) lines.emplace_back(line, number);
  }
  for (size_t i = 0; i < lines.size(); ++i) {
    const auto [line, line_number] = lines[i];
    json j;
    try {
      j = ParseJsonText(line, source, line_number);
    } catch (const TruncatedJsonError&) {
      // A killed run can leave its last line cut short; any other line was written whole.
      if (i + 1 == lines.size()) {
        file.dropped_partial = true;
        continue;
      }
      throw;
    }
    if (!j.is_object()) throw InputError(source, line_number, "", "not a JSON record (an object)");
    try {
      file.records.push_back(Record::FromJson(std::move(j)));
    } catch (const std::invalid_argument& e) {
      throw InputError(source, line_number, "", e.what());
    } catch (const json::exception& e) {  // a type the record's reader did not foresee
      throw InputError(source, line_number, "", OneLine(e.what()));
    }
    file.lines.emplace_back(line);
    file.line_numbers.push_back(line_number);
  }
  return file;
}

RecordFile ReadRecords(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return RecordFile();
    throw InputError(OneLine(path), 0, "", std::string("cannot read: ") + std::strerror(errno));
  }
  // The memory estimate, before anything is read (a regular file's size is known; anything
  // else is read no further than the same limit).
  const double budget = MemoryBudgetBytes();
  const auto max_bytes = static_cast<std::size_t>(budget / kRecordsMemoryPerByte);
  if (S_ISREG(st.st_mode)) {
    try {
      CheckMemoryEstimate(kRecordsMemoryPerByte * static_cast<double>(st.st_size),
                          "records",
                          MemoryText(static_cast<double>(st.st_size)) + " of records read whole");
    } catch (const std::invalid_argument& e) {
      throw InputError(OneLine(path), 0, "", e.what());
    }
  }
  const std::string text = ReadInputFile(path, max_bytes, "records file");
  return ParseRecords(text, OneLine(path));
}

std::string JoinLines(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& l : lines) text += l + "\n";
  return text;
}

}  // namespace ocpb
