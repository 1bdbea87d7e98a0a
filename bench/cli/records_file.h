// Records files (JSON Lines, one record per line): read typed, with each line as written.
#pragma once

#include <string>
#include <vector>

#include "bench/cli/record.h"

namespace ocpb {

/// A records file, read: each record typed, with its line as written.
struct RecordFile {
  std::vector<Record> records;
  std::vector<std::string> lines;  ///< the records' lines, verbatim (for rewriting the file)
  bool dropped_partial = false;    ///< a last line cut short by a killed run was dropped
  bool unterminated = false;       ///< the file does not end with a newline
};

/// Reads a records file (an empty RecordFile when it does not exist). A last line cut short by
/// a killed run is dropped (dropped_partial); any other malformed line, or a record with a field
/// of the wrong type, throws std::invalid_argument naming the file and the line. `unterminated`
/// tells that the file does not end with a newline (a whole last record whose '\n' was never
/// written): the next append would glue onto it, so a writer rewrites the file first (from
/// `lines`, so that no record is re-serialized).
RecordFile ReadRecords(const std::string& path);

/// The lines, each followed by a newline.
std::string JoinLines(const std::vector<std::string>& lines);

}  // namespace ocpb
