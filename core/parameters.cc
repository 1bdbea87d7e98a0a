#include "core/parameters.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/option_value.h"

namespace ocpb {

Parameters::Parameters(std::vector<ParameterSpec> specs) : specs_(std::move(specs)) {
  for (const ParameterSpec& s : specs_) values_[s.name] = s.default_value;
}

const ParameterSpec& Parameters::Spec(const std::string& name) const {
  for (const ParameterSpec& s : specs_) {
    if (s.name == name) return s;
  }
  throw std::invalid_argument("unknown parameter '" + name + "' (valid: " + Names() + ")");
}

std::string Parameters::Names() const {
  std::string out;
  for (const ParameterSpec& s : specs_) out += (out.empty() ? "" : ", ") + s.name;
  return out.empty() ? "none" : out;
}

void Parameters::Set(const std::string& name, const std::vector<double>& value) {
  const ParameterSpec& spec = Spec(name);
  if (value.size() != spec.default_value.size()) {
    throw std::invalid_argument("parameter '" + name + "' takes " +
                                std::to_string(spec.default_value.size()) + " value(s), got " +
                                std::to_string(value.size()));
  }
  for (double v : value) {
    if (!std::isfinite(v)) {
      throw std::invalid_argument("parameter '" + name + "' must be finite (got NaN or inf)");
    }
    const bool below = spec.min_exclusive ? !(v > spec.min) : v < spec.min;
    if (below || v > spec.max) {
      std::ostringstream os;
      os << "parameter '" << name << "' = " << v << " out of range: need "
         << (spec.min_exclusive ? "> " : ">= ") << spec.min;
      if (std::isfinite(spec.max)) os << " and <= " << spec.max;
      throw std::invalid_argument(os.str());
    }
    if (spec.integer && v != std::round(v)) {
      throw std::invalid_argument("parameter '" + name + "' must be an integer");
    }
  }
  values_[name] = value;
}

void Parameters::SetFromString(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == assignment.size()) {
    throw std::invalid_argument("malformed --set '" + assignment +
                                "': expected key=value or key=v1,v2");
  }
  const std::string key = assignment.substr(0, eq);
  const std::string list = assignment.substr(eq + 1);
  std::vector<double> values;
  // Split on every ',' ourselves: std::getline would silently drop a trailing empty item
  // ("tf=1," would read as "tf=1"), and a typo must not pass as a valid list.
  size_t begin = 0;
  for (int index = 1;; ++index) {
    const size_t comma = list.find(',', begin);
    const std::string item =
        list.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    if (item.empty()) {
      throw std::invalid_argument("malformed --set '" + assignment + "': value " +
                                  std::to_string(index) + " is empty");
    }
    // The one number grammar of every option and parameter text (core/option_value.h).
    const std::optional<double> v = ParseNumberText(item);
    if (!v) {
      throw std::invalid_argument("malformed --set '" + assignment + "': '" + item +
                                  "' is not a number");
    }
    values.push_back(*v);
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  Set(key, values);
}

OptionSpec ToOptionSpec(const ParameterSpec& p) {
  OptionSpec s;
  s.name = p.name;
  s.doc = p.help;
  s.bounds.min = p.min;
  s.bounds.max = p.max;
  s.bounds.min_exclusive = p.min_exclusive;
  if (p.default_value.size() == 1) {
    s.type = p.integer ? OptionType::kInteger : OptionType::kNumber;
    s.default_value = p.integer ? OptionValue(static_cast<long long>(p.default_value[0]))
                                : OptionValue(p.default_value[0]);
  } else {
    s.type = OptionType::kVector;
    s.size = static_cast<int>(p.default_value.size());
    s.default_value = p.default_value;
  }
  return s;
}

bool Parameters::Has(const std::string& name) const { return values_.count(name) > 0; }

const std::vector<double>& Parameters::Raw(const std::string& name) const {
  Spec(name);
  return values_.at(name);
}

double Parameters::Scalar(const std::string& name) const {
  const auto& v = Raw(name);
  if (v.size() != 1) throw std::logic_error("parameter '" + name + "' is not a scalar");
  return v[0];
}

int Parameters::Integer(const std::string& name) const {
  return static_cast<int>(std::lround(Scalar(name)));
}

Vec Parameters::Vector(const std::string& name) const {
  const auto& v = Raw(name);
  return Eigen::Map<const Vec>(v.data(), static_cast<Eigen::Index>(v.size()));
}

}  // namespace ocpb
