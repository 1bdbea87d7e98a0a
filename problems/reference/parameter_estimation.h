// Parameter estimation from observations as a multi-phase problem: the building block of the
// COPS 3.0 estimation problems (gasoil.h, methanol.h, pinene.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/multi_phase_ocp.h"

namespace ocpb {

/// The data of an estimation problem
///
///   minimize    sum_j || y(tau_j) - z_j ||^2           over the parameters theta
///   subject to  y' = g(y, theta),  y(t0) = y0 (given),  theta_lo <= theta <= theta_hi,
///
/// with observations z_j (ne values each) at t0 <= tau_1 < ... < tau_m. An observation at
/// tau_1 = t0 must equal y0 (its residual is then 0, a constant that is left out).
struct EstimationData {
  double t0 = 0.0;
  Vec y0;                     ///< the given initial state (ne)
  std::vector<double> times;  ///< the observation times tau_j
  Mat observations;           ///< ne x m: column j is z_j, observed at times[j]
  Vec parameter_lower;        ///< np
  Vec parameter_upper;        ///< np (+inf where unbounded)
  Vec parameter_guess;        ///< np, where methods start
};

/// One phase between consecutive observation times. Its state is x = (y, theta): the model's
/// ne states, then its np parameters as constant states (dynamics 0), because a phase of a
/// MultiPhaseOcp may not declare static parameters of its own; the links' continuity of every
/// component makes theta one value for all phases, and the first phase's initial state is free
/// in theta alone (theta(t0) in [theta_lo, theta_hi]), so theta is the decision that
/// SetStaticParameters would give (the same NLP: np variables per state point, all equal).
/// Its terminal cost is the squared residual || y(end) - z ||^2 at the observation ending it.
/// No control: each phase carries one control fixed at 0 by its bounds, which nothing reads
/// (AutoDiffOcp needs nu >= 1, and Ipopt removes fixed variables).
///
/// `Model` provides kStates (ne), kParameters (np) and
///   template <class T> static void Rates(const VecT<T, ne + np>& x, VecT<T, ne + np>* f)
/// writing f[0..ne) = g(y, theta) with y = x[0..ne) and theta = x[ne..ne + np).
template <class Model>
class ObservationPhase final
    : public AutoDiffOcp<ObservationPhase<Model>, Model::kStates + Model::kParameters, 1> {
 public:
  static constexpr int kNe = Model::kStates;
  static constexpr int kNp = Model::kParameters;
  static constexpr int kNx = kNe + kNp;

  /// The phase over [start, end] ending at `observation` (ne), starting from `start_state` (nx;
  /// for a later phase only a guess: the links set its start). `theta_bounds` (first phase
  /// only): x(start) free in theta within them, y(start) fixed.
  ObservationPhase(int index,
                   double start,
                   double end,
                   const Vec& start_state,
                   const Vec& observation,
                   const VectorBounds* theta_bounds)
      : index_(index), observation_(observation) {
    if (observation.size() != kNe || start_state.size() != kNx) {
      throw std::invalid_argument("ObservationPhase: wrong sizes");
    }
    this->SetHorizon(start, end);
    this->SetInitialState(start_state);
    this->SetControlSet(ControlSet::Box(Vec::Zero(1), Vec::Zero(1)));
    if (theta_bounds) {
      Vec lo = start_state, hi = start_state;
      lo.tail(kNp) = theta_bounds->lower;
      hi.tail(kNp) = theta_bounds->upper;
      this->SetInitialStateBounds(lo, hi);
    }
  }

  std::string name() const override { return "observation " + std::to_string(index_ + 1); }

  template <class T>
  void EvalDynamics(double, const VecT<T, kNx>& x, const VecT<T, 1>&, VecT<T, kNx>* f) const {
    Model::Rates(x, f);
    for (int k = kNe; k < kNx; ++k) (*f)[k] = T(0.0);
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, kNx>& x) const {
    T sum = T(0.0);
    for (int s = 0; s < kNe; ++s) {
      const T r = x[s] - observation_[s];
      sum += r * r;
    }
    return sum;
  }

 private:
  int index_;
  Vec observation_;
};

/// The estimation problem as phases of fixed durations between consecutive observation times
/// (the first from t0), joined by continuity of every state and parameter:
///   J = sum_j phi_j(x_j(end)) = sum_j || y(tau_j) - z_j ||^2.
/// Throws std::invalid_argument on inconsistent data.
template <class Model>
std::unique_ptr<MultiPhaseOcp> MakeEstimationProblem(const std::string& name,
                                                     const EstimationData& d) {
  using Phase = ObservationPhase<Model>;
  constexpr int ne = Phase::kNe, np = Phase::kNp;
  const int m = static_cast<int>(d.times.size());
  // Every rule up front, naming the field and the index (before any phase is built).
  const auto refuse = [&](const std::string& what) {
    throw std::invalid_argument(name + ": estimation data: " + what);
  };
  const auto need_size = [&](const char* field, Eigen::Index got, int want) {
    if (got != want) {
      refuse(std::string(field) + " has " + std::to_string(got) + " entries; the model needs " +
             std::to_string(want));
    }
  };
  need_size("y0", d.y0.size(), ne);
  need_size("parameter_lower", d.parameter_lower.size(), np);
  need_size("parameter_upper", d.parameter_upper.size(), np);
  need_size("parameter_guess", d.parameter_guess.size(), np);
  if (d.observations.rows() != ne || d.observations.cols() != m) {
    refuse("observations is " + std::to_string(d.observations.rows()) + " x " +
           std::to_string(d.observations.cols()) + "; it must be ne x m = " + std::to_string(ne) +
           " x " + std::to_string(m) + " (one column per entry of times)");
  }
  if (!std::isfinite(d.t0) || !d.y0.allFinite()) refuse("t0 and y0 must be finite");
  for (int j = 0; j < m; ++j) {
    if (!std::isfinite(d.times[j]) || !d.observations.col(j).allFinite()) {
      refuse("times[" + std::to_string(j) + "] and observations column " + std::to_string(j) +
             " must be finite");
    }
    if (d.times[j] < d.t0 || (j > 0 && !(d.times[j] > d.times[j - 1]))) {
      refuse("times[" + std::to_string(j) + "] = " + std::to_string(d.times[j]) +
             ": observation times must be >= t0 and strictly increasing");
    }
  }
  for (int i = 0; i < np; ++i) {
    const double lo = d.parameter_lower[i], hi = d.parameter_upper[i], g = d.parameter_guess[i];
    if (std::isnan(lo) || std::isnan(hi) || !(lo <= hi) || !std::isfinite(g) || g < lo || g > hi) {
      refuse("parameter " + std::to_string(i) + ": need parameter_lower <= parameter_guess <= " +
             "parameter_upper, the guess finite (got " + std::to_string(lo) +
             " <= " + std::to_string(g) + " <= " + std::to_string(hi) + ")");
    }
  }
  int first = 0;
  if (m >= 1 && std::abs(d.times[0] - d.t0) <= 1e-12 * std::max(1.0, std::abs(d.t0))) {
    // An observation at t0 of the given initial state: its residual is 0 when it equals y0.
    if ((d.observations.col(0) - d.y0).cwiseAbs().maxCoeff() > 0.0) {
      refuse("the observation at t0 (times[0]) differs from y0, the given initial state");
    }
    first = 1;
  }
  if (m - first < 1) refuse("times needs at least one observation after t0");
  const VectorBounds theta_bounds{d.parameter_lower, d.parameter_upper};
  std::vector<PhaseSpec> phases;
  double start = d.t0;
  for (int j = first; j < m; ++j) {
    const double end = d.times[j];
    Vec x0(Phase::kNx);
    // Where methods start: the previous observation (y0 first) and the parameter guess.
    x0.head(ne) = j == first ? d.y0 : Vec(d.observations.col(j - 1));
    x0.tail(np) = d.parameter_guess;
    auto phase = std::make_shared<Phase>(static_cast<int>(phases.size()),
                                         start,
                                         end,
                                         x0,
                                         Vec(d.observations.col(j)),
                                         phases.empty() ? &theta_bounds : nullptr);
    phases.push_back({std::move(phase), end - start, end - start});
    start = end;
  }
  std::vector<std::vector<PhaseLink>> links(phases.size() - 1,
                                            MultiPhaseOcp::Continuity(Phase::kNx));
  return std::make_unique<MultiPhaseOcp>(name, std::move(phases), std::move(links));
}

}  // namespace ocpb
