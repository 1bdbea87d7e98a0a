#include "problems/reference/free_start.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <stdexcept>

namespace ocpb {

std::vector<ParameterSpec> FreeStart::ParameterSpecs() {
  const double inf = std::numeric_limits<double>::infinity();
  return {
      {"w", {1.0}, "weight of the initial cost w/2 (x1(0) - a)^2", 0.0, inf, false},
      {"a", {0.0}, "target of x1(0) in the initial cost"},
      {"q", {4.0}, "weight of the terminal cost q/2 (x1(T) - b)^2", 0.0, inf, false},
      {"b", {2.0}, "target of x1(T) in the terminal cost"},
      {"lo", {-1.0}, "lower bound of x1(0) (<= 0)", -inf, 0.0, false},
      {"hi", {0.5}, "upper bound of x1(0) (>= 0)", 0.0, inf, false},
  };
}

FreeStart::FreeStart(const Parameters& params)
    : w_(params.Scalar("w")),
      a_(params.Scalar("a")),
      q_(params.Scalar("q")),
      b_(params.Scalar("b")),
      lo_(params.Scalar("lo")),
      hi_(params.Scalar("hi")) {
  SetHorizon(0.0, 1.0);
  SetInitialState(Eigen::Vector2d(0.0, 0.0));
  SetInitialStateBounds(Eigen::Vector2d(lo_, 0.0), Eigen::Vector2d(hi_, 0.0));
}

void FreeStart::MinimizeHamiltonian(double, ConstVecRef, ConstVecRef p, VecRef u) const {
  u[0] = p[1] > 0.0 ? -p[0] / p[1] : std::numeric_limits<double>::quiet_NaN();
}

FreeStart::Optimum FreeStart::AnalyticOptimum() const {
  const double T = tf() - t0();
  const double k = q_ / (1.0 + q_ * T);
  Optimum o;
  // w = k = 0 leaves J flat in x1(0): any start is optimal; take the nominal one.
  const double free = w_ + k > 0.0 ? (w_ * a_ + k * b_) / (w_ + k) : 0.0;
  o.x1_start = std::clamp(free, lo_, hi_);
  o.x1_end = (o.x1_start + q_ * T * b_) / (1.0 + q_ * T);
  o.J = 0.5 * w_ * (o.x1_start - a_) * (o.x1_start - a_) +
        0.5 * k * (o.x1_start - b_) * (o.x1_start - b_);
  return o;
}

Vec FreeStart::OptimalCostate() const {
  Vec p(2);
  p << q_ * (AnalyticOptimum().x1_end - b_), 1.0;
  return p;
}

ProblemInfo FreeStartProblemInfo() {
  ProblemInfo p;
  p.name = "free-start";
  p.description =
      "partly free initial state: x1(0) in [lo, hi] with an initial cost, Mayer form (bound "
      "active at the optimum)";
  p.parameters = FreeStart::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<FreeStart>(params);
  };
  p.default_intervals = 50;
  p.reference_value = FreeStart(Parameters(FreeStart::ParameterSpecs())).AnalyticOptimum().J;
  p.reference_source =
      "analytic J* = 1.025 (derived in problems/reference/free_start.h from the transversality "
      "conditions of a free initial state, Bryson-Ho Sec. 2.7)";
  p.hamiltonian_note =
      "not applicable: a free initial state (the paper's descent keeps x0 fixed); the family "
      "(hamiltonian-proximal, -al, -polish) on forward Euler takes it (a projected gradient "
      "step on x1(0) along lambda_0 + grad phi0, the polish's transversality rows), as "
      "indirect-newton does (p(t0) = -grad phi0, clipped by the bounds)";
  p.reference_costate = [](double) {
    return FreeStart(Parameters(FreeStart::ParameterSpecs())).OptimalCostate();
  };
  p.tags = {"free-initial-state", "mayer"};
  return p;
}

}  // namespace ocpb
