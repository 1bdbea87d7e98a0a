#include "problems/channel/true_channel.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace ocpb {

TrueChannelQuality::TrueChannelQuality(std::shared_ptr<const SimulatedChannel> truth,
                                       const QualityUnits& units)
    : truth_(std::move(truth)), units_(units) {
  if (truth_ == nullptr) throw std::invalid_argument("true channel: the realization is null");
  std::string error;
  if (!units_.IsValid(&error)) throw std::invalid_argument("true channel: " + error);
}

double TrueChannelQuality::At(const Eigen::Vector2d& q) const {
  // 1/CNR = 10^(-(Gamma_dB - N0)/10) in mW per mW of reference, times the unit scale.
  return units_.power_unit_scale * std::exp(-kDbToNeper * (truth_->GainAt(q) - units_.noise_dbm));
}

void TrueChannelQuality::Evaluate(const Eigen::Vector2d& q,
                                  double* s,
                                  Eigen::Vector2d* grad,
                                  Eigen::Matrix2d* hess) const {
  *s = At(q);
  if (grad) grad->setZero();
  if (hess) hess->setZero();
}

std::string TrueChannelQuality::Describe() const {
  std::ostringstream os;
  os << "true channel seed=" << truth_->seed << " cells=" << truth_->grid.resolution << "m";
  return os.str();
}

}  // namespace ocpb
