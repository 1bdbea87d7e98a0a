// The one way an IsValid(std::string* error) function reports a broken rule.
#pragma once

#include <string>

namespace ocpb {

/// Stores `why` in *error (when error is not null) and returns false, so that a validity check
/// reads `if (broken) return Invalid(error, "field: the rule, got value");`.
inline bool Invalid(std::string* error, const std::string& why) {
  if (error) *error = why;
  return false;
}

}  // namespace ocpb
