#include "transcriptions/nlp_scaling.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace ocpb {
namespace {

bool AllPositiveFinite(const Vec& v) {
  for (int i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i]) || !(v[i] > 0.0)) return false;
  }
  return true;
}

// Parses one positive finite number; throws naming `key` otherwise.
double ParsePositive(const std::string& key, const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  while (end && *end == ' ') ++end;
  if (text.empty() || end == begin || *end != '\0' || !std::isfinite(v) || !(v > 0.0)) {
    throw std::invalid_argument("option '" + key + "': '" + text +
                                "' is not a positive finite number");
  }
  return v;
}

Vec ParsePositiveList(const std::string& key, const std::string& value) {
  std::vector<double> out;
  size_t start = 0;
  while (true) {
    const size_t comma = value.find(',', start);
    out.push_back(ParsePositive(key, value.substr(start, comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return Eigen::Map<const Vec>(out.data(), static_cast<Eigen::Index>(out.size()));
}

}  // namespace

bool NlpScaling::IsValid(std::string* error) const {
  if (!std::isfinite(objective) || !(objective > 0.0)) {
    *error = "scaling: objective must be positive and finite";
    return false;
  }
  if (!AllPositiveFinite(state)) {
    *error = "scaling: every state scale must be positive and finite";
    return false;
  }
  if (!AllPositiveFinite(control)) {
    *error = "scaling: every control scale must be positive and finite";
    return false;
  }
  return true;
}

bool NlpScaling::IsValidFor(int nx, int nu, std::string* error) const {
  if (!IsValid(error)) return false;
  if (state.size() != 0 && state.size() != nx) {
    *error = "scaling: state scales must be empty or of size nx = " + std::to_string(nx);
    return false;
  }
  if (control.size() != 0 && control.size() != nu) {
    *error = "scaling: control scales must be empty or of size nu = " + std::to_string(nu);
    return false;
  }
  return true;
}

bool NlpScaling::IsIdentity() const {
  return objective == 1.0 && (state.size() == 0 || (state.array() == 1.0).all()) &&
         (control.size() == 0 || (control.array() == 1.0).all());
}

bool ParseNlpScalingOption(const std::string& key, const std::string& value, NlpScaling* scaling) {
  if (key == "objective_scale") {
    scaling->objective = ParsePositive(key, value);
  } else if (key == "state_scale") {
    scaling->state = ParsePositiveList(key, value);
  } else if (key == "control_scale") {
    scaling->control = ParsePositiveList(key, value);
  } else {
    return false;
  }
  return true;
}

}  // namespace ocpb
