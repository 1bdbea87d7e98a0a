#include "problems/channel/path_loss_only_channel.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace ocpb {

PathLossOnlyChannel::PathLossOnlyChannel(const ChannelParameters& parameters,
                                         const QualityUnits& units,
                                         double variance_db2)
    : parameters_(parameters), units_(units), variance_db2_(variance_db2) {
  std::string error;
  if (!parameters.IsValid(&error)) throw std::invalid_argument("path-loss channel: " + error);
  if (!units.IsValid(&error)) throw std::invalid_argument("path-loss channel: " + error);
  if (!(variance_db2 >= 0.0) || !std::isfinite(variance_db2)) {
    throw std::invalid_argument("path-loss channel: variance must be finite and >= 0");
  }
}

void PathLossOnlyChannel::Evaluate(const Eigen::Vector2d& q,
                                   double* s,
                                   Eigen::Vector2d* grad,
                                   Eigen::Matrix2d* hess) const {
  Eigen::Vector2d mg;
  Eigen::Matrix2d mh;
  const double mean = parameters_.PathLossDb(
      q, grad != nullptr || hess != nullptr ? &mg : nullptr, hess != nullptr ? &mh : nullptr);
  ComposeInverseCnr(mean,
                    mg,
                    mh,
                    variance_db2_,
                    Eigen::Vector2d::Zero(),
                    Eigen::Matrix2d::Zero(),
                    units_,
                    s,
                    grad,
                    hess);
}

std::string PathLossOnlyChannel::Describe() const {
  std::ostringstream os;
  os << "path-loss K_PL=" << parameters_.k_pl << " n_PL=" << parameters_.n_pl
     << " N0=" << units_.noise_dbm << "dBm";
  if (variance_db2_ > 0.0) os << " Sigma0=" << variance_db2_;
  return os.str();
}

}  // namespace ocpb
