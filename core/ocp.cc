#include "core/ocp.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace ocpb {

const char* ToString(TerminalMode mode) {
  return mode == TerminalMode::kPenalty ? "penalty" : "hard";
}

void Ocp::MinimizeHamiltonian(double, ConstVecRef, ConstVecRef, VecRef) const {
  throw std::logic_error("problem '" + name() + "' has no closed-form Hamiltonian minimizer");
}

void Ocp::MinimizeAndCompareHamiltonian(double t,
                                        ConstVecRef x,
                                        ConstVecRef p,
                                        ConstVecRef u,
                                        VecRef u_star,
                                        double* h_star,
                                        double* h_now,
                                        VecRef f) const {
  MinimizeHamiltonian(t, x, p, u_star);
  Dynamics(t, x, u_star, f);
  *h_star = p.dot(f) + RunningCost(t, x, u_star);
  Dynamics(t, x, u, f);
  *h_now = p.dot(f) + RunningCost(t, x, u);
}

void Ocp::MinimizeHamiltonianWithGradients(double t,
                                           ConstVecRef x,
                                           ConstVecRef p,
                                           VecRef u,
                                           VecRef f,
                                           MatRef fx,
                                           MatRef fu,
                                           double* L,
                                           VecRef Lx,
                                           VecRef Lu) const {
  MinimizeHamiltonian(t, x, p, u);
  DynamicsJacobian(t, x, u, f, fx, fu);
  RunningCostGradient(t, x, u, L, Lx, Lu);
}

double Ocp::TerminalPenalty(ConstVecRef x) const {
  if (npsi_ == 0) return 0.0;
  Vec psi(npsi_);
  TerminalConstraints(x, psi);
  return terminal_weights_.dot(psi.cwiseAbs2());
}

double Ocp::TerminalObjective(ConstVecRef x, TerminalMode mode) const {
  double value = TerminalCost(x);
  if (mode == TerminalMode::kPenalty) value += TerminalPenalty(x);
  return value;
}

void Ocp::TerminalObjectiveGradient(ConstVecRef x,
                                    TerminalMode mode,
                                    double* value,
                                    VecRef grad) const {
  TerminalCostGradient(x, value, grad);
  if (mode == TerminalMode::kPenalty && npsi_ > 0) {
    Vec psi(npsi_);
    Mat psix(npsi_, nx_);
    TerminalConstraintsJacobian(x, psi, psix);
    *value += terminal_weights_.dot(psi.cwiseAbs2());
    grad += psix.transpose() * (2.0 * terminal_weights_.cwiseProduct(psi));
  }
}

double Ocp::Hamiltonian(double t, ConstVecRef x, ConstVecRef u, ConstVecRef p) const {
  Vec f(nx_);
  Dynamics(t, x, u, f);
  return p.dot(f) + RunningCost(t, x, u);
}

void Ocp::SetDimensions(int nx, int nu, int npsi, int nc) {
  if (nx < 1 || nu < 1 || npsi < 0 || nc < 0) {
    throw std::invalid_argument(
        "problem dimensions must satisfy nx >= 1, nu >= 1, npsi >= 0, nc >= 0");
  }
  nx_ = nx;
  nu_ = nu;
  npsi_ = npsi;
  nc_ = nc;
  x0_ = Vec::Zero(nx);
  terminal_weights_ = Vec::Ones(npsi);
  terminal_weights_chosen_ = false;
  control_set_ = ControlSet::Unbounded(nu);
}

void Ocp::SetHorizon(double t0, double tf) {
  if (!std::isfinite(t0) || !std::isfinite(tf)) {
    throw std::invalid_argument("horizon: t0 and tf must be finite");
  }
  if (!(tf > t0)) throw std::invalid_argument("horizon: need tf > t0");
  if (free_final_time_ && !(t0 < free_final_time_->lower && free_final_time_->lower <= tf &&
                            tf <= free_final_time_->upper)) {
    std::ostringstream os;
    os << "horizon: [" << t0 << ", " << tf << "] does not fit the free final time's bounds ["
       << free_final_time_->lower << ", " << free_final_time_->upper
       << "] set before (need t0 < lower <= tf <= upper; call SetHorizon before "
          "SetFreeFinalTime)";
    throw std::invalid_argument(os.str());
  }
  t0_ = t0;
  tf_ = tf;
}

void Ocp::SetFreeFinalTime(double lower, double upper) {
  if (!std::isfinite(lower) || !std::isfinite(upper)) {
    throw std::invalid_argument("free final time: the bounds must be finite");
  }
  if (!(t0_ < lower && lower <= tf_ && tf_ <= upper)) {
    std::ostringstream os;
    os << "free final time: need t0 < lower <= tf <= upper (got t0 = " << t0_
       << ", lower = " << lower << ", tf = " << tf_ << ", upper = " << upper << ")";
    throw std::invalid_argument(os.str());
  }
  free_final_time_ = FreeFinalTime{lower, upper};
}

Vec Ocp::CheckedNominalControl() const {
  Vec u = NominalControl();
  if (u.size() != nu_ || !u.allFinite()) {
    throw std::invalid_argument("problem '" + name() +
                                "': NominalControl() must return nu = " + std::to_string(nu_) +
                                " finite values (got " + std::to_string(u.size()) +
                                (u.allFinite() ? ")" : ", not all finite)"));
  }
  return u;
}

std::optional<ControlTrajectory> Ocp::BaselinePlan(const TimeGrid&, std::string* why_not) const {
  if (why_not) *why_not = "problem '" + name() + "' defines no baseline plan";
  return std::nullopt;
}

bool Ocp::AdmitsFinalTime(double tf) const {
  if (!std::isfinite(tf)) return false;
  const double tol = 1e-9 * std::max({1.0, std::abs(t0_), std::abs(tf_)});
  if (!free_final_time_) return std::abs(tf - tf_) <= tol;
  return tf >= free_final_time_->lower - tol && tf <= free_final_time_->upper + tol;
}

bool Ocp::GridOnHorizon(const TimeGrid& grid, HorizonEnd end) const {
  if (grid.size() < 2) return false;
  const double tol = 1e-9 * std::max({1.0, std::abs(t0_), std::abs(tf_)});
  if (std::abs(grid.t0() - t0_) > tol) return false;
  return end == HorizonEnd::kAdmissible ? AdmitsFinalTime(grid.tf())
                                        : std::abs(grid.tf() - tf_) <= tol;
}

std::string Ocp::GridOffHorizon(const TimeGrid& grid, HorizonEnd end) const {
  if (GridOnHorizon(grid, end)) return "";
  if (grid.size() < 2) return "the grid has no interval (problem '" + name() + "')";
  std::ostringstream os;
  os << "the grid [" << grid.t0() << ", " << grid.tf() << "] does not span the horizon [" << t0_
     << ", ";
  if (end == HorizonEnd::kAdmissible && free_final_time_) {
    os << "T] with T in [" << free_final_time_->lower << ", " << free_final_time_->upper << "]";
  } else {
    os << tf_ << "]";
  }
  os << " of problem '" << name() << "'";
  return os.str();
}

void Ocp::SetInitialState(const Vec& x0) {
  if (np_ > 0) {
    throw std::invalid_argument(
        "initial state: set it before SetStaticParameters (which sets the parameters' guesses)");
  }
  if (x0.size() != nx_) throw std::invalid_argument("initial state: size must equal nx");
  if (!x0.allFinite()) throw std::invalid_argument("initial state: values must be finite");
  if (initial_state_bounds_ && initial_state_bounds_->Violation(x0) > 0.0) {
    throw std::invalid_argument(
        "initial state: x0 must lie within the initial-state bounds set before");
  }
  x0_ = x0;
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Throws std::invalid_argument naming `what` unless lower and upper have size n, no NaN, and
// lower <= upper componentwise.
void CheckBounds(const char* what, int n, const Vec& lower, const Vec& upper) {
  const std::string name(what);
  if (lower.size() != n || upper.size() != n) {
    throw std::invalid_argument(name +
                                ": lower and upper must have size nx = " + std::to_string(n));
  }
  for (int i = 0; i < n; ++i) {
    if (std::isnan(lower[i]) || std::isnan(upper[i])) {
      throw std::invalid_argument(name + ": component " + std::to_string(i) + " is NaN");
    }
    if (!(lower[i] <= upper[i]) || lower[i] == kInfinity || upper[i] == -kInfinity) {
      std::ostringstream os;
      os << name << ": component " << i
         << " needs lower <= upper and neither side empty (lower < +inf, upper > -inf; got ["
         << lower[i] << ", " << upper[i] << "])";
      throw std::invalid_argument(os.str());
    }
  }
}

}  // namespace

double VectorBounds::Violation(ConstVecRef v) const {
  double worst = 0.0;
  for (int i = 0; i < v.size(); ++i) {
    worst = std::max({worst, lower[i] - v[i], v[i] - upper[i]});
  }
  return worst;
}

VectorBounds Ocp::InitialNodeBounds() const {
  if (initial_state_bounds_) return *initial_state_bounds_;
  return VectorBounds{x0_, x0_};
}

void Ocp::SetStateBounds(const Vec& lower, const Vec& upper) {
  CheckBounds("state bounds", nx_, lower, upper);
  state_bounds_ = VectorBounds{lower, upper};
}

void Ocp::SetInitialStateBounds(const Vec& lower, const Vec& upper) {
  if (np_ > 0) {
    throw std::invalid_argument(
        "initial-state bounds: set them before SetStaticParameters (which sets the parameters' "
        "bounds)");
  }
  CheckBounds("initial-state bounds", nx_, lower, upper);
  VectorBounds b{lower, upper};
  if (b.Violation(x0_) > 0.0) {
    throw std::invalid_argument(
        "initial-state bounds: x0 (SetInitialState, where methods start) must lie within them");
  }
  free_initial_state_ = (b.lower.array() < b.upper.array()).any();
  initial_state_bounds_ = std::move(b);
}

void Ocp::SetBoundaryConstraints(const Vec& lower, const Vec& upper) {
  if (lower.size() != upper.size()) {
    throw std::invalid_argument("boundary constraints: lower and upper must have the same size");
  }
  for (int i = 0; i < lower.size(); ++i) {
    if (std::isnan(lower[i]) || std::isnan(upper[i]) || !(lower[i] <= upper[i]) ||
        lower[i] == kInfinity || upper[i] == -kInfinity) {
      std::ostringstream os;
      os << "boundary constraints: row " << i
         << " needs lower <= upper, no NaN, lower < +inf and upper > -inf (got [" << lower[i]
         << ", " << upper[i] << "])";
      throw std::invalid_argument(os.str());
    }
  }
  nb_ = static_cast<int>(lower.size());
  boundary_bounds_ = VectorBounds{lower, upper};
}

void Ocp::SetStaticParameters(const Vec& lower, const Vec& upper, const Vec& guess) {
  if (np_ > 0) throw std::invalid_argument("static parameters: declared twice");
  const int np = static_cast<int>(lower.size());
  if (np < 1 || np > nx_ || upper.size() != np || guess.size() != np) {
    throw std::invalid_argument(
        "static parameters: lower, upper and guess need one size np with 1 <= np <= nx = " +
        std::to_string(nx_));
  }
  for (int i = 0; i < np; ++i) {
    if (!std::isfinite(guess[i]) || std::isnan(lower[i]) || std::isnan(upper[i]) ||
        !(lower[i] <= guess[i] && guess[i] <= upper[i])) {
      std::ostringstream os;
      os << "static parameters: parameter " << i << " needs lower <= guess <= upper, guess finite"
         << " (got " << lower[i] << " <= " << guess[i] << " <= " << upper[i] << ")";
      throw std::invalid_argument(os.str());
    }
  }
  VectorBounds b = InitialNodeBounds();
  b.lower.tail(np) = lower;
  b.upper.tail(np) = upper;
  Vec x0 = x0_;
  x0.tail(np) = guess;
  if (b.Violation(x0) > 0.0) {
    throw std::invalid_argument(
        "static parameters: x0's other components lie outside their initial-state bounds");
  }
  x0_ = std::move(x0);
  free_initial_state_ = (b.lower.array() < b.upper.array()).any();
  initial_state_bounds_ = std::move(b);
  np_ = np;
}

void Ocp::CheckStaticParameterDynamics() const {
  if (np_ == 0) return;
  Vec u = CheckedNominalControl();
  control_set_.Project(u);
  // The value and its first derivatives at one point: a dynamics that is 0 there by chance (at
  // u = 0, say) still has a nonzero derivative somewhere in x or u.
  Vec f(nx_);
  Mat fx(nx_, nx_), fu(nx_, nu_);
  DynamicsJacobian(t0_, x0_, u, f, fx, fu);
  for (int i = nx_ - np_; i < nx_; ++i) {
    const double slope = std::max(fx.row(i).cwiseAbs().maxCoeff(), fu.row(i).cwiseAbs().maxCoeff());
    if (f[i] != 0.0 || slope != 0.0) {
      std::ostringstream os;
      os << "problem '" << name() << "': static parameter " << i - (nx_ - np_)
         << " (state component " << i << ") must have zero dynamics, got f[" << i << "] = " << f[i]
         << " with derivatives up to " << slope << " in x and u at (t0, x0, the nominal control)";
      throw std::invalid_argument(os.str());
    }
  }
}

double Ocp::BoundaryViolation(ConstVecRef x0, ConstVecRef xf) const {
  if (nb_ == 0) return 0.0;
  Vec b(nb_);
  BoundaryConstraints(x0, xf, b);
  if (!b.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  return boundary_bounds_.Violation(b);
}

namespace {

[[noreturn]] void MissingBoundary(const std::string& problem, const char* function) {
  throw std::logic_error("problem '" + problem +
                         "' declares boundary constraints but does not define " + function);
}

}  // namespace

void Ocp::BoundaryConstraints(ConstVecRef, ConstVecRef, VecRef) const {
  if (nb_ > 0) MissingBoundary(name(), "BoundaryConstraints");
}

void Ocp::BoundaryConstraintsJacobian(ConstVecRef, ConstVecRef, VecRef, MatRef, MatRef) const {
  if (nb_ > 0) MissingBoundary(name(), "BoundaryConstraintsJacobian");
}

void Ocp::BoundaryHessian(ConstVecRef, ConstVecRef, ConstVecRef, MatRef hess) const {
  if (nb_ > 0) MissingBoundary(name(), "BoundaryHessian");
  hess.setZero();
}

void Ocp::InitialCostGradient(ConstVecRef x0, double* phi0, VecRef grad) const {
  *phi0 = InitialCost(x0);
  grad.setZero();
}

void Ocp::InitialCostHessian(ConstVecRef, double, MatRef hess) const { hess.setZero(); }

void Ocp::SetTerminalWeights(const Vec& w) {
  if (w.size() != npsi_) throw std::invalid_argument("terminal weights: size must equal npsi");
  for (int i = 0; i < w.size(); ++i) {
    if (!std::isfinite(w[i]) || w[i] <= 0.0) {
      throw std::invalid_argument("terminal weights: every weight must be finite and > 0");
    }
  }
  terminal_weights_ = w;
  terminal_weights_chosen_ = true;
}

void Ocp::SetControlSet(const ControlSet& set) {
  if (set.dimension() != nu_) throw std::invalid_argument("control set: dimension must equal nu");
  control_set_ = set;
}

}  // namespace ocpb
