// Free final time by time scaling for problems with box-bounded controls: the shared form of
// "goddard" and "robot-arm".
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/reference/time_scaling.h"

namespace ocpb {

/// A problem with a free final time T and controls w in a box [lo, hi] (lo <= 0 <= hi), affine
/// in w,
///
///   minimize Phi(y(T), T)  subject to  y' = F0(y) + B(y) w,  y(0) = y0,  psi(y(T)) = 0,
///
/// is posed on s in [0, 1] with the time dilation sigma = dt/ds > 0 as a control, the scaled
/// control v = sigma w in place of w, and the physical time tau as the last state (a clock):
///
///   minimize    J = Phi(y(1), tau(1)) + eps (int_0^1 sigma^2 ds - tau(1)^2)
///   subject to  dy/ds = sigma F0(y) + B(y) v,  dtau/ds = sigma,  tau(0) = 0,
///               sigma lo <= v <= sigma hi   (path constraints, one per nonzero bound),
///               u = (v, sigma) in U = [sigma_max lo, sigma_max hi] x [sigma_min, sigma_max].
///
/// The same construction as ScaledMinTimeOcp (scaled_min_time.h), with a box for the disc:
///  - v = sigma w makes the dynamics linear in u and the cone sigma lo <= v <= sigma hi is
///    polyhedral, so the Hamiltonian is convex in u (with (w, sigma) it would be bilinear and the
///    pointwise minimizer's direction need not descend).
///  - Any positive sigma(s) with the same physical motion is the same solution, so Phi alone is
///    degenerate in sigma's profile; the eps term is eps Var(sigma) >= 0, zero exactly when sigma
///    is constant (= T). Every motion has a constant-sigma realization, so the optimum of J is
///    the optimum of Phi with sigma = T; the records' J is then Phi. A large eps also makes the
///    trapezoid transcription the constant-step scheme COPS uses.
///
/// Hamiltonian: H = sigma a + s^T v + eps sigma^2 with a = p^T F0 + p_tau (p_tau = 1 - 2 eps
/// tau(1), constant) and s = B^T p, from NW + 1 evaluations of the physical dynamics. The method
/// cannot take the path constraints; HamiltonianReformulation() returns ScaledFreeTimePenalty
/// (below): the cone as the penalty rho sum_i dist(v_i, [sigma lo_i, sigma hi_i])^2, with its exact
/// minimizer.
///
/// `Derived` has state dimension NX (the physical state, then the clock at index NX - 1), NW
/// physical controls, NCONE = the number of nonzero entries of lo and hi, and provides
///   template <class T> void EvalPhysical(const VecT<T, NX>& x, const VecT<T, NW>& w,
///                                        VecT<T, NX>* f) const;  // F0 + B w in f[0 .. NX-2]
///   template <class T> T EvalPhysicalCost(const VecT<T, NX>& x) const;  // Phi(y, tau)
///   template <class T> void EvalTerminalConstraints(const VecT<T, NX>& x,
///                                                   VecT<T, NPSI>* psi) const;
/// and calls InitializeScaling() from its constructor. Records' time axis is s, their last state
/// is t, and the physical control is w = v / sigma.
template <class Derived, int NX, int NW, int NPSI, int NCONE>
class ScaledFreeTimeOcp : public AutoDiffOcp<Derived, NX, NW + 1, NPSI, NCONE> {
 public:
  static constexpr int kNu = NW + 1;

  /// Parameters shared by every problem of this form, with the problem's defaults.
  static std::vector<ParameterSpec> ScalingParameterSpecs(double C,
                                                          double eps,
                                                          double sigma_min,
                                                          double sigma_max) {
    return TimeScalingParameterSpecs(C, eps, sigma_min, sigma_max, "rho dist(v, sigma [lo, hi])^2");
  }

  double eps() const { return eps_; }
  double rho() const { return rho_; }
  double sigma_min() const { return sigma_min_; }
  double sigma_max() const { return sigma_max_; }
  /// The physical control bounds lo and hi.
  const std::array<double, NW>& lower() const { return lo_; }
  const std::array<double, NW>& upper() const { return hi_; }

  template <class T>
  void EvalDynamics(double, const VecT<T, NX>& x, const VecT<T, kNu>& u, VecT<T, NX>* f) const {
    // sigma F0 + B v = Phys(v) + (sigma - 1) Phys(0), Phys being affine in its control.
    VecT<T, NX> f0;
    VecT<T, NW> zero;
    for (int i = 0; i < NW; ++i) zero[i] = T(0.0);
    Physical(x, zero, &f0);
    Physical(x, VecT<T, NW>(u.template head<NW>()), f);
    for (int i = 0; i < NX; ++i) (*f)[i] += (u[NW] - 1.0) * f0[i];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, NX>&, const VecT<T, kNu>& u) const {
    return eps_ * u[NW] * u[NW];
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, NX>& x) const {
    return derived().EvalPhysicalCost(x) - eps_ * x[NX - 1] * x[NX - 1];
  }
  /// v_i - sigma hi_i <= 0 for each hi_i != 0, then sigma lo_i - v_i <= 0 for each lo_i != 0.
  template <class T>
  void EvalPathConstraints(double,
                           const VecT<T, NX>&,
                           const VecT<T, kNu>& u,
                           VecT<T, NCONE>* c) const {
    int k = 0;
    for (int i = 0; i < NW; ++i) {
      if (hi_[i] != 0.0) (*c)[k++] = u[i] - u[NW] * hi_[i];
    }
    for (int i = 0; i < NW; ++i) {
      if (lo_[i] != 0.0) (*c)[k++] = u[NW] * lo_[i] - u[i];
    }
  }

  /// H's drift a = p^T F0 (clock included) and switching vector s = B^T p at (x, p).
  void HamiltonianCoefficients(ConstVecRef x, ConstVecRef p, double* a, double s[NW]) const {
    const VecT<double, NX> xs(x);
    VecT<double, NX> f0, fi;
    VecT<double, NW> w = VecT<double, NW>::Zero();
    Physical(xs, w, &f0);
    *a = p.dot(f0);
    for (int i = 0; i < NW; ++i) {
      w[i] = 1.0;
      Physical(xs, w, &fi);
      w[i] = 0.0;
      s[i] = p.dot(fi - f0);
    }
  }

  /// The start every method uses without an initial guess: the problem's nominal physical
  /// control and time dilation (a rough guess of T), as (sigma w, sigma).
  Vec NominalControl() const override { return nominal_; }

  std::unique_ptr<Ocp> HamiltonianReformulation(
      const HamiltonianReformulationOptions& options) const override;

 protected:
  /// Reads C, eps, rho and the sigma bounds, and sets the horizon [0, 1], the initial state
  /// (y0, 0), the terminal weights, U, the cone's bounds and the nominal control. Throws
  /// std::invalid_argument when sigma_min >= sigma_max, when a bound has the wrong sign, or when
  /// NCONE is not the number of nonzero bounds.
  void InitializeScaling(const Parameters& params,
                         const Vec& y0,
                         const std::array<double, NW>& lo,
                         const std::array<double, NW>& hi,
                         const Vec& w_nominal,
                         double sigma_nominal) {
    const TimeScalingSettings settings = TimeScalingSettings::Read(params, derived().name());
    eps_ = settings.eps;
    rho_ = settings.rho;
    sigma_min_ = settings.sigma_min;
    sigma_max_ = settings.sigma_max;
    int nonzero = 0;
    for (int i = 0; i < NW; ++i) {
      if (!(lo[i] <= 0.0 && 0.0 <= hi[i] && lo[i] < hi[i])) {
        throw std::invalid_argument(derived().name() + ": control bounds need lo <= 0 <= hi");
      }
      nonzero += (lo[i] != 0.0) + (hi[i] != 0.0);
    }
    if (nonzero != NCONE) throw std::logic_error(derived().name() + ": NCONE != nonzero bounds");
    lo_ = lo;
    hi_ = hi;
    this->SetDimensions(NX, kNu, NPSI, NCONE);
    this->SetHorizon(0.0, 1.0);
    Vec x0 = Vec::Zero(NX);
    x0.head(NX - 1) = y0;
    this->SetInitialState(x0);
    this->SetTerminalWeights(Vec::Constant(NPSI, params.Scalar("C")));
    Vec ulo(kNu), uhi(kNu);
    for (int i = 0; i < NW; ++i) {
      ulo[i] = sigma_max_ * lo[i];
      uhi[i] = sigma_max_ * hi[i];
    }
    ulo[NW] = sigma_min_;
    uhi[NW] = sigma_max_;
    this->SetControlSet(ControlSet::Box(ulo, uhi));
    nominal_ = Vec(kNu);
    nominal_ << sigma_nominal * w_nominal, sigma_nominal;
  }

 private:
  template <class D, int N, int W, int P, int C>
  friend class ScaledFreeTimePenalty;

  const Derived& derived() const { return static_cast<const Derived&>(*this); }
  /// The unscaled dynamics: the problem's F0 + B w, and the clock's 1.
  template <class T>
  void Physical(const VecT<T, NX>& x, const VecT<T, NW>& w, VecT<T, NX>* f) const {
    derived().EvalPhysical(x, w, f);
    (*f)[NX - 1] = T(1.0);
  }

  double eps_ = 1.0;
  double rho_ = 1e4;
  double sigma_min_ = 0.0;
  double sigma_max_ = 1.0;
  std::array<double, NW> lo_{};
  std::array<double, NW> hi_{};
  Vec nominal_;
};

/// The Hamiltonian method's form of a ScaledFreeTimeOcp P: the cone sigma lo <= v <= sigma hi as
/// the exterior penalty rho sum_i dist(v_i, [sigma lo_i, sigma hi_i])^2 in L (convex in u, zero
/// exactly on P's cone), no path constraints, everything else P's. Its controls are judged on P
/// (the evaluator reports the cone's violation as the path violation).
///
/// Exact minimizer of H = a sigma + s^T v + eps sigma^2 + penalty over U. For fixed sigma, v_i
/// goes to the cone's bound b_i against s_i (lo_i if s_i > 0, hi_i if s_i < 0) and past it by
/// d_i = min(|s_i| / (2 rho), (sigma_max - sigma) |b_i|) (U's bound). What is left, h(sigma), is
/// convex (a partial minimum of a jointly convex function over a fixed box) with the continuous,
/// increasing, piecewise-linear derivative
///   h'(sigma) = a + 2 eps sigma + sum_i g_i(sigma),
///   g_i = -|s_i| |b_i|                               for sigma <= sigma_max - |s_i| / (2 rho
///   |b_i|), g_i = -2 rho b_i^2 (sigma_max - sigma)           above;
/// sigma* is its root in [sigma_min, sigma_max] (or an end), found exactly by linear
/// interpolation between the breakpoints that bracket the sign change.
template <class Derived, int NX, int NW, int NPSI, int NCONE>
class ScaledFreeTimePenalty final
    : public AutoDiffOcp<ScaledFreeTimePenalty<Derived, NX, NW, NPSI, NCONE>, NX, NW + 1, NPSI, 0> {
 public:
  static constexpr int kNu = NW + 1;

  ScaledFreeTimePenalty(const Derived& problem, double rho, double eps) : problem_(problem) {
    CheckReformulationWeights(problem.name(), rho, eps);
    problem_.eps_ = eps;
    rho_ = rho;
    this->SetDimensions(NX, kNu, NPSI, 0);
    this->SetHorizon(problem.t0(), problem.tf());
    this->SetInitialState(problem.x0());
    this->SetTerminalWeights(problem.terminal_weights());
    this->SetControlSet(problem.control_set());
  }

  std::string name() const override { return problem_.name() + "+penalty"; }
  double rho() const { return rho_; }
  double eps() const { return problem_.eps_; }

  template <class T>
  void EvalDynamics(double t, const VecT<T, NX>& x, const VecT<T, kNu>& u, VecT<T, NX>* f) const {
    problem_.EvalDynamics(t, x, u, f);
  }
  template <class T>
  T EvalRunningCost(double t, const VecT<T, NX>& x, const VecT<T, kNu>& u) const {
    T L = problem_.EvalRunningCost(t, x, u);
    for (int i = 0; i < NW; ++i) {
      const T above = u[i] - u[NW] * problem_.hi_[i];
      const T below = u[NW] * problem_.lo_[i] - u[i];
      if (ValueOf(above) > 0.0) L += rho_ * above * above;
      if (ValueOf(below) > 0.0) L += rho_ * below * below;
    }
    return L;
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, NX>& x) const {
    return problem_.EvalTerminalCost(x);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, NX>& x, VecT<T, NPSI>* psi) const {
    problem_.EvalTerminalConstraints(x, psi);
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double, ConstVecRef x, ConstVecRef p, VecRef u) const override {
    double a, s[NW];
    problem_.HamiltonianCoefficients(x, p, &a, s);
    const double eps = problem_.eps_;
    const double smin = problem_.sigma_min_, smax = problem_.sigma_max_;
    double b[NW];
    for (int i = 0; i < NW; ++i) {
      b[i] = s[i] > 0.0 ? problem_.lo_[i] : (s[i] < 0.0 ? problem_.hi_[i] : 0.0);
    }
    auto slope = [&](double sigma) {
      double g = a + 2.0 * eps * sigma;
      for (int i = 0; i < NW; ++i) {
        const double c = std::abs(b[i]);
        if (c == 0.0) continue;
        const double knee = smax - std::abs(s[i]) / (2.0 * rho_ * c);
        g += sigma <= knee ? -std::abs(s[i]) * c : -2.0 * rho_ * c * c * (smax - sigma);
      }
      return g;
    };
    // Breakpoints of the piecewise-linear slope inside [smin, smax], in order.
    std::array<double, NW + 2> points{};
    int n = 0;
    points[n++] = smin;
    for (int i = 0; i < NW; ++i) {
      const double c = std::abs(b[i]);
      if (c == 0.0) continue;
      const double knee = smax - std::abs(s[i]) / (2.0 * rho_ * c);
      if (knee > smin && knee < smax) points[n++] = knee;
    }
    points[n++] = smax;
    // Insertion sort of at most NW + 2 entries (std::sort trips GCC 12's -Warray-bounds here).
    for (int k = 1; k < n; ++k) {
      for (int j = k; j > 0 && points[j] < points[j - 1]; --j) std::swap(points[j], points[j - 1]);
    }
    double sigma = smax;
    double left = slope(points[0]);
    if (left >= 0.0) {
      sigma = smin;
    } else {
      for (int k = 1; k < n; ++k) {
        const double right = slope(points[k]);
        if (right >= 0.0) {
          // Linear on [points[k-1], points[k]]: the root by interpolation is exact.
          sigma = points[k - 1] + (points[k] - points[k - 1]) * (-left) / (right - left);
          break;
        }
        left = right;
      }
    }
    sigma = std::clamp(sigma, smin, smax);
    for (int i = 0; i < NW; ++i) {
      const double c = std::abs(b[i]);
      const double d = std::min(std::abs(s[i]) / (2.0 * rho_), (smax - sigma) * c);
      if (s[i] > 0.0) {
        u[i] = sigma * problem_.lo_[i] - (c > 0.0 ? d : 0.0);
      } else if (s[i] < 0.0) {
        u[i] = sigma * problem_.hi_[i] + (c > 0.0 ? d : 0.0);
      } else {
        u[i] = 0.0;
      }
    }
    u[NW] = sigma;
  }
  Vec NominalControl() const override { return problem_.NominalControl(); }

 private:
  Derived problem_;
  double rho_ = 1e4;
};

template <class Derived, int NX, int NW, int NPSI, int NCONE>
std::unique_ptr<Ocp> ScaledFreeTimeOcp<Derived, NX, NW, NPSI, NCONE>::HamiltonianReformulation(
    const HamiltonianReformulationOptions& options) const {
  const double eps = eps_ > 0.0 ? eps_ : options.regularization.value_or(1.0);
  return std::make_unique<ScaledFreeTimePenalty<Derived, NX, NW, NPSI, NCONE>>(
      derived(), options.path_penalty.value_or(rho_), eps);
}

}  // namespace ocpb
