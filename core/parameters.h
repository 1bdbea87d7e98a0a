// Named, typed, validated problem parameters (`--set key=value`, suite overrides).
#pragma once

#include <limits>
#include <map>
#include <string>
#include <vector>

#include "core/option_schema.h"
#include "core/types.h"

namespace ocpb {

/// The declaration of one parameter: name, default, help, allowed range, size.
struct ParameterSpec {
  std::string name;
  std::vector<double> default_value;  ///< a scalar is a vector of size 1
  std::string help;
  double min = -std::numeric_limits<double>::infinity();  ///< every component >= min
  double max = std::numeric_limits<double>::infinity();   ///< every component <= max
  bool min_exclusive = false;                             ///< then every component > min
  bool integer = false;                                   ///< components must be integers
};

/// The parameter as a general option description (`ocpbench describe problem`): a number, an
/// integer, or a vector of the default's length, with the same range.
OptionSpec ToOptionSpec(const ParameterSpec& spec);

/// Values for a list of declared parameters. Every setter validates and throws
/// std::invalid_argument with a one-line message naming the parameter and the rule.
class Parameters {
 public:
  Parameters() = default;
  explicit Parameters(std::vector<ParameterSpec> specs);

  /// Sets `name`; the size must match the default's, values finite and in range.
  void Set(const std::string& name, const std::vector<double>& value);
  /// Parses "key=v" or "key=v1,v2,..." and sets it.
  void SetFromString(const std::string& assignment);

  bool Has(const std::string& name) const;
  double Scalar(const std::string& name) const;
  int Integer(const std::string& name) const;
  Vec Vector(const std::string& name) const;
  const std::vector<double>& Raw(const std::string& name) const;

  const std::vector<ParameterSpec>& specs() const { return specs_; }
  /// Every parameter's current value, in declaration order.
  const std::map<std::string, std::vector<double>>& values() const { return values_; }
  /// "a, b, c": the valid names (for error messages).
  std::string Names() const;

 private:
  const ParameterSpec& Spec(const std::string& name) const;
  std::vector<ParameterSpec> specs_;
  std::map<std::string, std::vector<double>> values_;
};

}  // namespace ocpb
