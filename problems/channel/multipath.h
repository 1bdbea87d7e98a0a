// Small-scale (multipath) fading in the dB domain.
#pragma once

#include <string>

#include "problems/channel/random_stream.h"

namespace ocpb {

/// How the simulator draws MP(q), independently at every grid point.
enum class MultipathModel {
  /// Rician fading in the linear domain with unit mean power:
  ///   h = sqrt(K / (K + 1)) + sqrt(1 / (2 (K + 1))) (n1 + i n2),  MP = 10 log10 |h|^2,
  /// n1, n2 iid N(0, 1). With K = 14.56 the dB-domain standard deviation is 1.64 dB and the dB
  /// mean -0.288 dB (RicianDbMoments), the paper's rho.
  kRician,
  /// MP ~ N(0, rho^2) in dB (log-normal in the linear domain), rho = ChannelParameters::rho.
  kLogNormal,
  /// MP = 0.
  kNone,
};
const char* ToString(MultipathModel model);
/// "rician", "lognormal" or "none"; throws std::invalid_argument otherwise.
MultipathModel MultipathModelFromString(const std::string& name);

struct MultipathOptions {
  MultipathModel model = MultipathModel::kRician;
  double rician_k = 14.56;  ///< K_ric, the Rician K-factor (linear, > 0)

  bool IsValid(std::string* error) const;
};

/// One draw of MP in dB; `rho` is used by kLogNormal only.
double DrawMultipathDb(const MultipathOptions& options, double rho, RandomStream* stream);

/// Mean and standard deviation of 10 log10 |h|^2 for Rician fading with K-factor k and unit
/// mean power, by numerical integration of the non-central chi-square density of |h|^2
/// (composite Simpson in ln |h|^2; relative accuracy about 1e-9).
struct DbMoments {
  double mean_db = 0.0;
  double std_db = 0.0;
};
DbMoments RicianDbMoments(double k);

}  // namespace ocpb
