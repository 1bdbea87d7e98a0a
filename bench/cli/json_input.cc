#include "bench/cli/json_input.h"

#include <string>

#include "core/memory_budget.h"

namespace ocpb {
namespace {

using nlohmann::json;

// A position in the document: its line within `source` and its column (from 1).
struct Place {
  int line = 1;
  int column = 1;
};

Place PlaceOf(std::string_view text, std::size_t offset, int first_line) {
  Place p;
  p.line = first_line;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++p.line;
      line_start = i + 1;
    }
  }
  p.column = static_cast<int>(offset - line_start) + 1;
  return p;
}

// The byte offset of the first array or object that opens deeper than `max_depth`, or npos.
// Brackets inside strings do not count (a backslash escapes the next character there).
std::size_t TooDeepAt(std::string_view text, int max_depth) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string_view::npos;
}

// Only the error of a SAX pass: its byte offset and the library's reason.
class ErrorFinder : public json::json_sax_t {
 public:
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return true; }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t position,
                   const std::string& last_token,
                   const nlohmann::detail::exception& ex) override {
    offset = position;
    // A number beyond double is reported at the end of its token: placed at its start.
    token_size = ex.id == 406 ? last_token.size() : 1;
    reason = ex.what();
    return false;
  }
  std::size_t offset = 0;      // one past the last character read
  std::size_t token_size = 0;  // back from offset to the error's column
  std::string reason;
};

// The library's message without its "[json.exception.parse_error.101] parse error at line 1,
// column 5: " prefix (the caller names the place in the file).
std::string Reason(std::string what) {
  if (what.rfind("[json.exception.", 0) == 0) {
    const std::size_t close = what.find("] ");
    if (close != std::string::npos) what = what.substr(close + 2);
  }
  const std::size_t column = what.find(", column ");
  if (what.rfind("parse error", 0) == 0 && column != std::string::npos) {
    const std::size_t colon = what.find(": ", column);
    if (colon != std::string::npos) what = what.substr(colon + 2);
  }
  return OneLine(what);
}

}  // namespace

json ParseJsonText(std::string_view text,
                   const std::string& source,
                   int first_line,
                   int max_depth) {
  const std::size_t deep = TooDeepAt(text, max_depth);
  if (deep != std::string_view::npos) {
    const Place p = PlaceOf(text, deep, first_line);
    throw InputError(source,
                     p.line,
                     "",
                     "nesting deeper than " + std::to_string(max_depth) + " levels at column " +
                         std::to_string(p.column));
  }
  try {
    return json::parse(text);
  } catch (const json::exception& first) {
    // parse_error, or out_of_range for a number beyond double (1e999): find where, once more
    // through the SAX interface, which reports the offset of every kind of error.
    ErrorFinder finder;
    json::sax_parse(text, &finder);
    const std::string why = finder.reason.empty() ? first.what() : finder.reason;
    // The column of the character the parser stopped at (of a too large number: its start).
    const std::size_t at =
        finder.offset >= finder.token_size ? finder.offset - finder.token_size : 0;
    const Place p = PlaceOf(text, at, first_line);
    const std::string rule =
        "not valid JSON at column " + std::to_string(p.column) + ": " + Reason(why);
    if (finder.offset >= text.size()) throw TruncatedJsonError(source, p.line, "", rule);
    throw InputError(source, p.line, "", rule);
  }
}

namespace {

// A file's size limit, lowered to what the machine's memory budget can parse.
std::size_t JsonByteLimit(std::size_t max_bytes) {
  const double affordable = MemoryBudgetBytes() / kJsonMemoryPerByte;
  return affordable < static_cast<double>(max_bytes) ? static_cast<std::size_t>(affordable)
                                                     : max_bytes;
}

}  // namespace

json LoadJsonFile(const std::string& path, std::size_t max_bytes, const std::string& what) {
  const std::string text = ReadInputFile(path, JsonByteLimit(max_bytes), what);
  return ParseJsonText(text, OneLine(path));
}

namespace {

// Walks a document's text beside the parsed document, noting each value's line. The text is
// valid JSON (ParseJsonText accepted it); where text and document disagree (a key given twice:
// the document keeps one value), the text's value is skipped and nothing is noted for it.
class LineWalker {
 public:
  LineWalker(std::string_view text, int first_line, std::unordered_map<const json*, int>* lines)
      : text_(text), line_(first_line), lines_(lines) {}

  void Walk(const json* value) {
    SkipSpace();
    if (pos_ >= text_.size()) return;
    if (value != nullptr) (*lines_)[value] = line_;
    const char c = text_[pos_];
    if (c == '{') {
      ++pos_;
      while (true) {
        SkipSpace();
        if (pos_ >= text_.size() || text_[pos_] == '}') break;
        const std::string key = String();
        SkipSpace();
        ++pos_;  // ':'
        const json* child = nullptr;
        if (value != nullptr && value->is_object()) {
          const auto it = value->find(key);
          if (it != value->end()) child = &*it;
        }
        Walk(child);
        SkipSpace();
        if (pos_ < text_.size() && text_[pos_] == ',') ++pos_;
      }
      ++pos_;
    } else if (c == '[') {
      ++pos_;
      size_t index = 0;
      while (true) {
        SkipSpace();
        if (pos_ >= text_.size() || text_[pos_] == ']') break;
        const json* child = value != nullptr && value->is_array() && index < value->size()
                                ? &(*value)[index]
                                : nullptr;
        Walk(child);
        ++index;
        SkipSpace();
        if (pos_ < text_.size() && text_[pos_] == ',') ++pos_;
      }
      ++pos_;
    } else if (c == '"') {
      String();
    } else {
      while (pos_ < text_.size() &&
             std::string_view(",]} \t\r\n").find(text_[pos_]) == std::string_view::npos) {
        ++pos_;
      }
    }
  }

 private:
  void SkipSpace() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' ||
                                   text_[pos_] == '\r' || text_[pos_] == '\n')) {
      line_ += text_[pos_] == '\n';
      ++pos_;
    }
  }
  // A string token at pos_, decoded (escapes included) by the JSON library.
  std::string String() {
    const size_t start = pos_++;
    while (pos_ < text_.size() && text_[pos_] != '"') pos_ += text_[pos_] == '\\' ? 2 : 1;
    ++pos_;
    return json::parse(text_.substr(start, pos_ - start)).get<std::string>();
  }

  std::string_view text_;
  size_t pos_ = 0;
  int line_;
  std::unordered_map<const json*, int>* lines_;
};

}  // namespace

JsonLines::JsonLines(std::string_view text, const json& document, int first_line) {
  LineWalker(text, first_line, &lines_).Walk(&document);
}

int JsonLines::LineOf(const json& value) const {
  const auto it = lines_.find(&value);
  return it == lines_.end() ? 0 : it->second;
}

JsonInputFile::JsonInputFile(const std::string& path,
                             std::size_t max_bytes,
                             const std::string& what,
                             const std::string& source)
    : source_(source) {
  std::string text;
  try {
    text = ReadInputFile(path, JsonByteLimit(max_bytes), what);
  } catch (const InputError& e) {
    throw InputError(source_, 0, "", e.rule());  // named as the caller names the file
  }
  document_ = ParseJsonText(text, source_);
  lines_ = JsonLines(text, document_);
}

void JsonInputFile::Fail(const json& value,
                         const std::string& field,
                         const std::string& rule) const {
  throw InputError(source_, LineOf(value), field, rule);
}

}  // namespace ocpb
