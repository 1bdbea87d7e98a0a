// Records files (JSON Lines, one record per line): read typed, with each line as written.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "bench/cli/record.h"

namespace ocpb {

/// A records file, read: each record typed, with its line as written.
struct RecordFile {
  std::vector<Record> records;
  std::vector<std::string> lines;  ///< the records' lines, verbatim (for rewriting the file)
  std::vector<int> line_numbers;   ///< each record's line in the file (from 1)
  bool dropped_partial = false;    ///< a last line cut short by a killed run was dropped
  bool unterminated = false;       ///< the file does not end with a newline

  /// Drops every record whose key an earlier record of the file already has (two runs that
  /// wrote one file before runs took the folder's lock; see bench/cli/output_place.h) and
  /// returns how many were dropped: the first record of a case stays.
  int DropDuplicateKeys();
};

/// OCPBench's estimate of the memory reading a records file takes, per byte of the file: its
/// text, each line kept verbatim, and the typed records (numbers as doubles, the bulky JSON
/// parts moved, not copied, out of each line's document) and one line's document at a time.
inline constexpr double kRecordsMemoryPerByte = 4.0;

/// Reads a records file (an empty RecordFile when it does not exist). Before reading, its size
/// is checked against the memory estimate (kRecordsMemoryPerByte against MemoryBudgetBytes);
/// each line is parsed within kMaxJsonDepth. A last line cut short by a killed run is dropped
/// (dropped_partial); any other malformed line, or a record with a field of the wrong type,
/// throws InputError "FILE:LINE: FIELD: rule" (an std::invalid_argument: `ocpbench` exits 2).
/// `unterminated` tells that the file does not end with a newline (a whole last record whose
/// '\n' was never written): the next append would glue onto it, so a writer rewrites the file
/// first (from `lines`, so that no record is re-serialized).
RecordFile ReadRecords(const std::string& path);

/// The same for records given as text; `source` names them in errors (the fuzzer, tests).
RecordFile ParseRecords(std::string_view text, const std::string& source);

/// The lines, each followed by a newline.
std::string JoinLines(const std::vector<std::string>& lines);

}  // namespace ocpb
