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
    *error =
        "scaling: state scales (state_scale) must be empty or of size nx = " + std::to_string(nx) +
        " (got " + std::to_string(state.size()) + ")";
    return false;
  }
  if (control.size() != 0 && control.size() != nu) {
    *error = "scaling: control scales (control_scale) must be empty or of size nu = " +
             std::to_string(nu) + " (got " + std::to_string(control.size()) + ")";
    return false;
  }
  return true;
}

bool NlpScaling::IsIdentity() const {
  return objective == 1.0 && (state.size() == 0 || (state.array() == 1.0).all()) &&
         (control.size() == 0 || (control.array() == 1.0).all());
}

}  // namespace ocpb
