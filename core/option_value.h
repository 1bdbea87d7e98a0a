// Typed option values, the one text grammar they are read from, and maps of them by name.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace ocpb {

/// Reads a number in OCPBench's one grammar for every number written as text (command-line
/// `--option` and `--set` values, text values in suite files): decimal or scientific notation as
/// in C ("500", "-2.5", "1e-8", "1E3", ".5", "+7"), or "inf" / "-inf" / "infinity" (any case).
/// The whole text must be the number: no spaces, no trailing characters, no hexadecimal, no
/// NaN, nothing beyond the range of a double (1e999 is refused rather than read as infinity).
/// Returns nullopt when `text` is not such a number. Whether infinity is acceptable is the
/// option's rule (OptionSpec), not the grammar's.
std::optional<double> ParseNumberText(std::string_view text);

/// One option value: empty (unset), a number, an integer, a boolean, a text, or a vector of
/// numbers. A value given by a user may be text in any option's grammar ("500" for an integer
/// option); OptionSpec::Resolve turns it into the option's own type once, before any solving.
class OptionValue {
 public:
  enum class Kind { kEmpty, kNumber, kInteger, kBool, kText, kVector };

  OptionValue() = default;
  OptionValue(double v) : value_(v) {}  // NOLINT: implicit, so that {"tol", 1e-8} reads well
  OptionValue(int v) : value_(static_cast<std::int64_t>(v)) {}        // NOLINT
  OptionValue(long v) : value_(static_cast<std::int64_t>(v)) {}       // NOLINT
  OptionValue(long long v) : value_(static_cast<std::int64_t>(v)) {}  // NOLINT
  OptionValue(bool v) : value_(v) {}                                  // NOLINT
  OptionValue(const char* v) : value_(std::string(v)) {}              // NOLINT
  OptionValue(std::string v) : value_(std::move(v)) {}                // NOLINT
  OptionValue(std::vector<double> v) : value_(std::move(v)) {}        // NOLINT

  Kind kind() const { return static_cast<Kind>(value_.index()); }
  bool empty() const { return kind() == Kind::kEmpty; }
  /// The value as the kind it holds; each throws std::logic_error for another kind.
  double number() const;
  std::int64_t integer() const;
  bool boolean() const;
  const std::string& text() const;
  const std::vector<double>& vector() const;

  /// The canonical text of the value (what records and case keys show; the grammar reads it
  /// back to the same value): integers in decimal; numbers in the shortest form that reads back
  /// to the same double, fixed for decimal exponents -4..15 ("0.0001", "2000") and d.ddde+XX
  /// otherwise ("1e-05", "1.5e+20"), "inf" / "-inf"; booleans "true" / "false"; vectors as
  /// comma-separated numbers; text as is; "" when empty.
  std::string ToText() const;
  /// A short description of the kind for messages: "number", "integer", "boolean", "text",
  /// "list of numbers", "nothing".
  const char* KindName() const;

  friend bool operator==(const OptionValue& a, const OptionValue& b) {
    return a.value_ == b.value_;
  }

 private:
  std::variant<std::monostate, double, std::int64_t, bool, std::string, std::vector<double>> value_;
};

/// Option values by name, ordered by name (so that every listing and case key is stable).
/// A map given to a solver holds what the user chose; the solver's OptionSchema resolves it
/// (unknown names refused, each value checked and converted to its option's type).
class OptionMap {
 public:
  using Entries = std::map<std::string, OptionValue>;

  OptionMap() = default;
  OptionMap(std::initializer_list<Entries::value_type> entries) : entries_(entries) {}
  /// Text values, as the command line gives them (each is resolved by the option's grammar).
  OptionMap(const std::map<std::string, std::string>& text);  // NOLINT: implicit on purpose

  void Set(const std::string& name, OptionValue value) { entries_[name] = std::move(value); }
  bool Has(const std::string& name) const { return entries_.count(name) > 0; }
  /// nullptr when `name` is not set.
  const OptionValue* Find(const std::string& name) const;
  void Erase(const std::string& name) { entries_.erase(name); }
  bool empty() const { return entries_.empty(); }
  size_t size() const { return entries_.size(); }
  Entries::const_iterator begin() const { return entries_.begin(); }
  Entries::const_iterator end() const { return entries_.end(); }
  const Entries& entries() const { return entries_; }

  /// Every value's canonical text (OptionValue::ToText), by name.
  std::map<std::string, std::string> ToText() const;

  friend bool operator==(const OptionMap& a, const OptionMap& b) {
    return a.entries_ == b.entries_;
  }

 private:
  Entries entries_;
};

}  // namespace ocpb
