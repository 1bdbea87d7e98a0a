// The interface between a channel model and the problems that use it.
#pragma once

#include <string>

#include <Eigen/Core>

namespace ocpb {

/// s(q) = E[1 / CNR(q)] at a position q in the plane, in the units the cost uses, with its
/// gradient and Hessian with respect to q. Implementations: the exact Gaussian-process
/// predictor, a precomputed smooth map of it, or a deterministic path-loss-only model.
class ChannelQuality {
 public:
  virtual ~ChannelQuality() = default;
  /// Value, gradient (2) and Hessian (2x2) of s at q. `grad` and `hess` may be null.
  virtual void Evaluate(const Eigen::Vector2d& q, double* s, Eigen::Vector2d* grad,
                        Eigen::Matrix2d* hess) const = 0;
  /// A short description recorded with results ("gp-exact m=500", "map bicubic 0.1 m", ...).
  virtual std::string Describe() const = 0;
};

}  // namespace ocpb
