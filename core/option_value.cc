#include "core/option_value.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <system_error>

namespace ocpb {
namespace {

bool EqualsIgnoringCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    const char x = (a[i] >= 'A' && a[i] <= 'Z') ? static_cast<char>(a[i] - 'A' + 'a') : a[i];
    if (x != b[i]) return false;
  }
  return true;
}

// The shortest text that reads back to `v`, written the way the rest of OCPBench writes
// numbers (fixed notation for decimal exponents -4..15, else d.ddde+XX): the same text the
// fmt library gives for "{}", so that case keys written before and after typed options agree.
std::string ShortestText(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::isnan(v)) return "nan";
  char buffer[64];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::scientific);
  const std::string sci(buffer, result.ptr);  // [-]d[.ddd]e(+|-)XX
  const size_t e = sci.find('e');
  const int exponent = std::stoi(sci.substr(e + 1));
  if (exponent < -4 || exponent >= 16) return sci;
  const bool negative = sci[0] == '-';
  std::string digits;
  for (size_t i = negative ? 1 : 0; i < e; ++i) {
    if (sci[i] != '.') digits += sci[i];
  }
  std::string out = negative ? "-" : "";
  if (exponent < 0) {
    out += "0." + std::string(static_cast<size_t>(-exponent - 1), '0') + digits;
  } else if (static_cast<int>(digits.size()) <= exponent + 1) {
    out += digits + std::string(static_cast<size_t>(exponent + 1) - digits.size(), '0');
  } else {
    out += digits.substr(0, static_cast<size_t>(exponent) + 1) + "." +
           digits.substr(static_cast<size_t>(exponent) + 1);
  }
  return out;
}

}  // namespace

std::optional<double> ParseNumberText(std::string_view text) {
  if (text.empty()) return std::nullopt;
  bool negative = false;
  std::string_view body = text;
  if (body[0] == '+' || body[0] == '-') {
    negative = body[0] == '-';
    body.remove_prefix(1);
  }
  if (body.empty() || body[0] == '+' || body[0] == '-') return std::nullopt;
  if (EqualsIgnoringCase(body, "inf") || EqualsIgnoringCase(body, "infinity")) {
    const double inf = std::numeric_limits<double>::infinity();
    return negative ? -inf : inf;
  }
  // Digits, at most one '.', an optional exponent: checked here so that from_chars' other
  // spellings (nan, hexadecimal without prefix) never pass.
  size_t i = 0, mantissa_digits = 0;
  while (i < body.size() && body[i] >= '0' && body[i] <= '9') ++i, ++mantissa_digits;
  if (i < body.size() && body[i] == '.') {
    ++i;
    while (i < body.size() && body[i] >= '0' && body[i] <= '9') ++i, ++mantissa_digits;
  }
  if (mantissa_digits == 0) return std::nullopt;
  if (i < body.size() && (body[i] == 'e' || body[i] == 'E')) {
    ++i;
    if (i < body.size() && (body[i] == '+' || body[i] == '-')) ++i;
    size_t exponent_digits = 0;
    while (i < body.size() && body[i] >= '0' && body[i] <= '9') ++i, ++exponent_digits;
    if (exponent_digits == 0) return std::nullopt;
  }
  if (i != body.size()) return std::nullopt;
  double value = 0.0;
  const auto [end, error] = std::from_chars(body.data(), body.data() + body.size(), value);
  if (error != std::errc() || end != body.data() + body.size() || !std::isfinite(value)) {
    return std::nullopt;  // out of range (1e999) or, defensively, anything not consumed
  }
  return negative ? -value : value;
}

double OptionValue::number() const {
  if (const double* v = std::get_if<double>(&value_)) return *v;
  throw std::logic_error(std::string("OptionValue: a ") + KindName() + ", not a number");
}

std::int64_t OptionValue::integer() const {
  if (const std::int64_t* v = std::get_if<std::int64_t>(&value_)) return *v;
  throw std::logic_error(std::string("OptionValue: a ") + KindName() + ", not an integer");
}

bool OptionValue::boolean() const {
  if (const bool* v = std::get_if<bool>(&value_)) return *v;
  throw std::logic_error(std::string("OptionValue: a ") + KindName() + ", not a boolean");
}

const std::string& OptionValue::text() const {
  if (const std::string* v = std::get_if<std::string>(&value_)) return *v;
  throw std::logic_error(std::string("OptionValue: a ") + KindName() + ", not a text");
}

const std::vector<double>& OptionValue::vector() const {
  if (const auto* v = std::get_if<std::vector<double>>(&value_)) return *v;
  throw std::logic_error(std::string("OptionValue: a ") + KindName() + ", not a list of numbers");
}

std::string OptionValue::ToText() const {
  switch (kind()) {
    case Kind::kEmpty:
      return "";
    case Kind::kNumber:
      return ShortestText(number());
    case Kind::kInteger:
      return std::to_string(integer());
    case Kind::kBool:
      return boolean() ? "true" : "false";
    case Kind::kText:
      return text();
    case Kind::kVector: {
      std::string out;
      // Appended piecewise: GCC 12 -O2 reports a false -Wrestrict on `"," + text` here.
      for (double v : vector()) {
        if (!out.empty()) out += ',';
        out += ShortestText(v);
      }
      return out;
    }
  }
  return "";
}

const char* OptionValue::KindName() const {
  switch (kind()) {
    case Kind::kEmpty:
      return "nothing";
    case Kind::kNumber:
      return "number";
    case Kind::kInteger:
      return "integer";
    case Kind::kBool:
      return "boolean";
    case Kind::kText:
      return "text";
    case Kind::kVector:
      return "list of numbers";
  }
  return "value";
}

OptionMap::OptionMap(const std::map<std::string, std::string>& text) {
  for (const auto& [name, value] : text) entries_[name] = OptionValue(value);
}

const OptionValue* OptionMap::Find(const std::string& name) const {
  const auto it = entries_.find(name);
  return it == entries_.end() ? nullptr : &it->second;
}

std::map<std::string, std::string> OptionMap::ToText() const {
  std::map<std::string, std::string> out;
  for (const auto& [name, value] : entries_) out[name] = value.ToText();
  return out;
}

}  // namespace ocpb
