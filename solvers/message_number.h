// How solver messages print a number: `significant_digits` significant digits in the stream's
// default notation (so 1e-08, 0.5, 475.7744896). One helper, so that every message of the
// Hamiltonian methods prints numbers alike.
#pragma once

#include <sstream>
#include <string>

namespace ocpb {

inline std::string MessageNumber(double v, int significant_digits = 10) {
  std::ostringstream os;
  os.precision(significant_digits);
  os << v;
  return os.str();
}

}  // namespace ocpb
