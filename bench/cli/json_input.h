// JSON input files (suites, records read by --resume and merge, initial guesses): parsed within
// a nesting limit, every error an InputError "FILE:LINE: ..." (core/input_file.h).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "core/input_file.h"

namespace ocpb {

/// The deepest nesting of arrays and objects an input document may have. OCPBench's own
/// documents nest at most 5 deep (a record's s_map rows, a suite's method options); the parser
/// is iterative, but copying, comparing and writing a document recurse, so a document nested a
/// million deep would overflow the stack there.
inline constexpr int kMaxJsonDepth = 64;

/// Size limits of the JSON inputs (bytes). A suite is written by hand; a record keeps a
/// trajectory and a channel map (a few MB for N = 10^5); a records file is read one line at a
/// time (bench/cli/records_file.h has its whole-file memory estimate).
inline constexpr std::size_t kMaxSuiteFileBytes = std::size_t{16} << 20;
inline constexpr std::size_t kMaxRecordBytes = std::size_t{256} << 20;

/// OCPBench's estimate of the memory a JSON document takes per byte of its text while it is
/// read: the text and the parsed document (a number is a 16-byte value, an object entry a
/// tree node of about 80 bytes). LoadJsonFile and JsonInputFile read at most
/// MemoryBudgetBytes() / kJsonMemoryPerByte bytes, whatever their own limit.
inline constexpr double kJsonMemoryPerByte = 4.0;

/// The InputError of a document that ends before it is complete (a line cut short by a killed
/// run): the parser stopped at the end of the text.
class TruncatedJsonError : public InputError {
 public:
  using InputError::InputError;
};

/// Parses one JSON document: a whole file, or one line of a JSON Lines file that starts at line
/// `first_line` of `source`. Throws InputError "SOURCE:LINE: not valid JSON at column C: why"
/// (a syntax error, a number beyond double such as 1e999) or "SOURCE:LINE: nesting deeper than
/// 64 levels at column C" before building anything; TruncatedJsonError when the text ends
/// before the document does.
nlohmann::json ParseJsonText(std::string_view text,
                             const std::string& source,
                             int first_line = 1,
                             int max_depth = kMaxJsonDepth);

/// ReadInputFile (size limit, `what` names the kind of file) and ParseJsonText.
nlohmann::json LoadJsonFile(const std::string& path,
                            std::size_t max_bytes,
                            const std::string& what);

/// Where each value of a parsed document starts in its text, so that an error about a field
/// names its line. Built by walking the text beside the document (each value once, nesting at
/// most kMaxJsonDepth), after ParseJsonText accepted it.
class JsonLines {
 public:
  JsonLines() = default;
  JsonLines(std::string_view text, const nlohmann::json& document, int first_line = 1);
  /// The line where `value` (a value inside the document) starts; 0 when it is not one.
  int LineOf(const nlohmann::json& value) const;

 private:
  std::unordered_map<const nlohmann::json*, int> lines_;
};

/// A JSON input file, read and parsed once, that can name the line of any of its values:
/// the one way an input file's field errors are reported ("SOURCE:LINE: FIELD: rule").
class JsonInputFile {
 public:
  /// LoadJsonFile, with errors naming `source` (the path, or "--initial-guess PATH").
  JsonInputFile(const std::string& path,
                std::size_t max_bytes,
                const std::string& what,
                const std::string& source);

  const nlohmann::json& document() const { return document_; }
  const std::string& source() const { return source_; }
  int LineOf(const nlohmann::json& value) const { return lines_.LineOf(value); }
  const JsonLines& lines() const { return lines_; }
  /// Throws InputError "SOURCE:LINE: FIELD: rule" with the line where `value` starts.
  [[noreturn]] void Fail(const nlohmann::json& value,
                         const std::string& field,
                         const std::string& rule) const;

 private:
  std::string source_;
  nlohmann::json document_;
  JsonLines lines_;
};

}  // namespace ocpb
