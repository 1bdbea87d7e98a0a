#include "problems/channel/multipath.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ocpb {

const char* ToString(MultipathModel model) {
  switch (model) {
    case MultipathModel::kRician:
      return "rician";
    case MultipathModel::kLogNormal:
      return "lognormal";
    case MultipathModel::kNone:
      return "none";
  }
  return "?";
}

MultipathModel MultipathModelFromString(const std::string& name) {
  if (name == "rician") return MultipathModel::kRician;
  if (name == "lognormal") return MultipathModel::kLogNormal;
  if (name == "none") return MultipathModel::kNone;
  throw std::invalid_argument("unknown multipath model '" + name +
                              "' (valid: rician, lognormal, none)");
}

bool MultipathOptions::IsValid(std::string* error) const {
  if (model == MultipathModel::kRician && (!(rician_k > 0.0) || !std::isfinite(rician_k))) {
    if (error != nullptr) *error = "Rician K-factor must be finite and > 0";
    return false;
  }
  return true;
}

double DrawMultipathDb(const MultipathOptions& options, double rho, RandomStream* stream) {
  switch (options.model) {
    case MultipathModel::kRician: {
      const double k = options.rician_k;
      const double los = std::sqrt(k / (k + 1.0));
      const double sigma = std::sqrt(0.5 / (k + 1.0));
      const double re = los + sigma * stream->Normal();
      const double im = sigma * stream->Normal();
      return 10.0 * std::log10(re * re + im * im);
    }
    case MultipathModel::kLogNormal:
      return rho * stream->Normal();
    case MultipathModel::kNone:
      return 0.0;
  }
  return 0.0;
}

DbMoments RicianDbMoments(double k) {
  if (!(k > 0.0) || !std::isfinite(k)) {
    throw std::invalid_argument("Rician K-factor must be finite and > 0");
  }
  // Density of x = |h|^2 (unit mean): f(x) = (K+1) exp(-K - (K+1) x) I0(2 sqrt(K (K+1) x)).
  // With x = e^t the density of t is f(e^t) e^t; I0 is scaled to avoid overflow:
  // I0(z) = exp(z) i0e(z), so the exponent is -K - (K+1) x + z.
  auto density = [k](double t) {
    const double x = std::exp(t);
    const double z = 2.0 * std::sqrt(k * (k + 1.0) * x);
    double scaled_i0;
    if (z < 500.0) {
      scaled_i0 = std::cyl_bessel_i(0.0, z) * std::exp(-z);
    } else {  // asymptotic series of exp(-z) I0(z), relative error < 1e-12 here
      const double u = 1.0 / (8.0 * z);
      scaled_i0 = (1.0 + u * (1.0 + u * (4.5 + u * 37.5))) / std::sqrt(2.0 * std::numbers::pi * z);
    }
    return (k + 1.0) * std::exp(-k - (k + 1.0) * x + z) * scaled_i0 * x;
  };
  // Composite Simpson in t = ln x over [lo, hi] with a step resolving the bulk (its width in t
  // is about the relative standard deviation of |h|^2, sqrt(2K + 1) / (K + 1)).
  const double lo = -40.0, hi = std::log(40.0 / (k + 1.0) + 1.0) + 2.0;
  const double width = std::sqrt(2.0 * k + 1.0) / (k + 1.0);
  int n = static_cast<int>(std::ceil((hi - lo) / std::min(0.01, width / 50.0)));
  n += n % 2;
  const double dt = (hi - lo) / n;
  double p0 = 0.0, p1 = 0.0, p2 = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double t = lo + i * dt;
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    const double f = w * density(t);
    p0 += f;
    p1 += f * t;
    p2 += f * t * t;
  }
  const double to_db = 10.0 / std::log(10.0);
  const double m1 = p1 / p0;
  const double m2 = std::max(p2 / p0 - m1 * m1, 0.0);
  return {to_db * m1, to_db * std::sqrt(m2)};
}

}  // namespace ocpb
