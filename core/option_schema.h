// Option descriptions: what a solver, a transcription or a driver accepts, with defaults and
// rules, and the one place where given values are checked and turned into their types.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "core/option_value.h"

namespace ocpb {

/// The type of an option's value.
enum class OptionType {
  kNumber,   ///< a double (ranges in OptionBounds; infinity only where the bounds admit it)
  kInteger,  ///< an integer (a number with an integral value, "1e3" included)
  kBool,     ///< true / false (also 1 / 0)
  kEnum,     ///< one of a fixed list of names (OptionSpec::choices)
  kText,     ///< any text (a file name, an Ipopt string option without a fixed list)
  kVector,   ///< a list of numbers (text "1,2,3"; each component within the bounds)
};
const char* ToString(OptionType type);

/// The admissible values of a number, an integer, or each component of a vector.
struct OptionBounds {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;  ///< then values must be > min
  bool max_exclusive = false;  ///< then values must be < max
  /// Numbers only: whether +-infinity is a value ("no limit"); always within min and max.
  bool allow_infinite = false;

  static OptionBounds Any() { return {}; }
  static OptionBounds AtLeast(double min) { return {min, kInf, false, false, false}; }
  static OptionBounds Above(double min) { return {min, kInf, true, false, false}; }
  /// (min, max)
  static OptionBounds Open(double min, double max) { return {min, max, true, true, false}; }
  /// [min, max]
  static OptionBounds Closed(double min, double max) { return {min, max, false, false, false}; }
  /// (min, max]
  static OptionBounds OpenClosed(double min, double max) { return {min, max, true, false, false}; }
  /// The same bounds with +-infinity admitted (where within them).
  OptionBounds WithInfinity() const {
    OptionBounds b = *this;
    b.allow_infinite = true;
    return b;
  }

  bool Contains(double v) const;
  /// "any number", "> 0", ">= 1", "in (0, 1)", "in [1, 60]", with ", or inf" where admitted.
  std::string Describe() const;

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
};

/// The description of one option: name, type, default, rule and a one-line doc.
struct OptionSpec {
  std::string name;
  OptionType type = OptionType::kNumber;
  std::string doc;  ///< one line: what the option does
  /// The default, of the option's type; empty when the option is unset by default, which then
  /// means what `unset_doc` says ("the problem's own default", "no limit").
  OptionValue default_value;
  std::string unset_doc;
  OptionBounds bounds;               ///< kNumber, kInteger, kVector components
  std::vector<std::string> choices;  ///< kEnum: the admissible names
  int size = 0;                      ///< kVector: exact length, 0: any length >= 1

  /// `given` as a value of this option's type, or std::invalid_argument with a one-line message
  /// "option 'NAME': must be RULE (got 'TEXT')". Typed values are converted where no
  /// information is lost (an integer for a number; an integral number for an integer; 0 / 1 for
  /// a boolean; a number for a vector of length 1); text is read by the one grammar
  /// (ParseNumberText; "true"/"false"/"1"/"0"; "a,b,c" for vectors). An empty value resolves to
  /// itself (unset).
  OptionValue Resolve(const OptionValue& given) const;
  /// The rule as text: "number in (0, 1)", "integer >= 0", "true or false", "one of: a, b",
  /// "list of 3 numbers > 0", "text".
  std::string Rule() const;
  /// The default as text, or "unset (" + unset_doc + ")".
  std::string DefaultText() const;
};

/// The options one owner (a solver, a transcription, a driver) accepts. Besides its own specs
/// it may forward a prefix to another schema: "hamiltonian.max_iterations" of indirect-newton
/// is the hamiltonian solver's max_iterations.
class OptionSchema {
 public:
  explicit OptionSchema(std::string owner = "") : owner_(std::move(owner)) {}

  /// Adds an option. Throws std::logic_error for a duplicate name, an empty name, a default
  /// that breaks its own rule, or an enum without choices (a programming error of the owner).
  void Add(OptionSpec spec);
  /// Forwards every "PREFIX.NAME" to `nested` (copied; its owner is used in messages).
  void AddNested(const std::string& prefix, const OptionSchema& nested, std::string doc);

  const std::string& owner() const { return owner_; }
  const std::vector<OptionSpec>& specs() const { return specs_; }
  /// The spec `name` resolves against (a nested schema's for "PREFIX.NAME"), or nullptr.
  const OptionSpec* Find(const std::string& name) const;
  bool Contains(const std::string& name) const { return Find(name) != nullptr; }
  /// "a, b, c, hamiltonian.<option>": every name, for "valid:" lists.
  std::string Names() const;

  /// One value resolved (OptionSpec::Resolve). Throws std::invalid_argument "OWNER: unknown
  /// option 'NAME' (valid: ...)" or "OWNER option 'NAME': must be ... (got ...)".
  OptionValue ResolveOne(const std::string& name, const OptionValue& value) const;
  /// Every entry of `given` resolved; the first bad entry throws (see ResolveOne).
  OptionMap Resolve(const OptionMap& given) const;
  /// Every option, one per line: "  name  type  default  rule  doc" (`ocpbench describe`).
  std::string Describe() const;

 private:
  struct Nested {
    std::string prefix;
    std::vector<OptionSpec> specs;
    std::string owner;
    std::string doc;
  };
  std::string owner_;
  std::vector<OptionSpec> specs_;
  std::vector<Nested> nested_;
};

}  // namespace ocpb
