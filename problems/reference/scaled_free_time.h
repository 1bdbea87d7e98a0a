// Free final time by time scaling for problems with box-bounded controls: the shared form of
// "goddard" and "robot-arm".
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"

namespace ocpb {

/// A problem with a free final time T and controls w in a box W,
///
///   minimize Phi(y(T), T)  subject to  y' = F(y, w),  y(0) = y0,  psi(y(T)) = 0,  w in W,
///
/// is posed on s in [0, 1] with the time dilation sigma = dt/ds > 0 as one more control and the
/// physical time tau as the last state (a clock):
///
///   minimize    J = Phi(y(1), tau(1)) + eps (int_0^1 sigma^2 ds - tau(1)^2)
///   subject to  dy/ds = sigma F(y, w),  dtau/ds = sigma,  tau(0) = 0,
///               u = (w, sigma) in W x [sigma_min, sigma_max].
///
/// As in ScaledMinTimeOcp (scaled_min_time.h), any positive sigma(s) with the same physical
/// motion is the same solution, so Phi alone is degenerate in sigma's profile; the eps term is
/// eps Var(sigma) >= 0 (Jensen: int sigma^2 >= (int sigma)^2 on [0, 1]), zero exactly when sigma
/// is constant (= T). Every physical motion has a constant-sigma realization, so the optimum of
/// J is the optimum of Phi, reached with sigma = T constant; the records' J is then Phi.
///
/// Not for the Hamiltonian method: sigma F(y, w) is bilinear in (w, sigma), so H is not convex in
/// u and its pointwise minimizer need not give a descent direction (with the brachistochrone in
/// this form the Armijo search failed at the first iteration). ScaledMinTimeOcp avoids it with
/// the scaled control v = sigma w and a convex cone; for a box W that is the polyhedral cone
/// sigma lo <= v <= sigma hi, which is not written. These problems therefore have no
/// Hamiltonian minimizer, and the registry marks the method not applicable.
///
/// `Derived` has state dimension NX (the physical state, then the clock at index NX - 1), NW
/// physical controls, and provides
///   template <class T> void EvalPhysical(const VecT<T, NX>& x, const VecT<T, NW + 1>& u,
///                                        VecT<T, NX>* f) const;  // F(y, w) in f[0 .. NX-2]
///   template <class T> T EvalPhysicalCost(const VecT<T, NX>& x) const;  // Phi(y, tau)
///   template <class T> void EvalTerminalConstraints(const VecT<T, NX>& x,
///                                                   VecT<T, NPSI>* psi) const;
/// (u's last entry, sigma, is not for EvalPhysical to use), and calls InitializeScaling() from its
/// constructor. Records' time axis is s and their last state is t.
template <class Derived, int NX, int NW, int NPSI>
class ScaledFreeTimeOcp : public AutoDiffOcp<Derived, NX, NW + 1, NPSI, 0> {
 public:
  static constexpr int kNu = NW + 1;

  /// Parameters shared by every problem of this form, with the problem's defaults.
  static std::vector<ParameterSpec> ScalingParameterSpecs(double C,
                                                          double eps,
                                                          double sigma_min,
                                                          double sigma_max) {
    return {
        {"C", {C}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
        {"eps",
         {eps},
         "weight of the variance of sigma in J (0: Phi alone, degenerate in sigma)",
         0.0,
         1e300},
        {"sigma_min",
         {sigma_min},
         "lower bound of the time dilation sigma = dt/ds",
         0.0,
         1e300,
         true},
        {"sigma_max", {sigma_max}, "upper bound of the time dilation sigma", 0.0, 1e300, true},
    };
  }

  double eps() const { return eps_; }

  template <class T>
  void EvalDynamics(double, const VecT<T, NX>& x, const VecT<T, kNu>& u, VecT<T, NX>* f) const {
    derived().EvalPhysical(x, u, f);
    (*f)[NX - 1] = T(1.0);
    for (int i = 0; i < NX; ++i) (*f)[i] *= u[NW];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, NX>&, const VecT<T, kNu>& u) const {
    return eps_ * u[NW] * u[NW];
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, NX>& x) const {
    return derived().EvalPhysicalCost(x) - eps_ * x[NX - 1] * x[NX - 1];
  }

  /// The start every method uses without an initial guess: the problem's nominal physical
  /// control and time dilation (a rough guess of T).
  Vec NominalControl() const override { return nominal_; }

 protected:
  /// Reads C, eps and the sigma bounds, and sets the horizon [0, 1], the initial state (y0, 0),
  /// the terminal weights, U = [w_lo, w_hi] x [sigma_min, sigma_max] and the nominal control
  /// (w_nominal, sigma_nominal). Throws std::invalid_argument when sigma_min >= sigma_max.
  void InitializeScaling(const Parameters& params,
                         const Vec& y0,
                         const Vec& w_lo,
                         const Vec& w_hi,
                         const Vec& w_nominal,
                         double sigma_nominal) {
    eps_ = params.Scalar("eps");
    const double sigma_min = params.Scalar("sigma_min");
    const double sigma_max = params.Scalar("sigma_max");
    if (!(sigma_min < sigma_max)) {
      throw std::invalid_argument(derived().name() + ": sigma_min must be < sigma_max");
    }
    this->SetDimensions(NX, kNu, NPSI, 0);
    this->SetHorizon(0.0, 1.0);
    Vec x0 = Vec::Zero(NX);
    x0.head(NX - 1) = y0;
    this->SetInitialState(x0);
    this->SetTerminalWeights(Vec::Constant(NPSI, params.Scalar("C")));
    Vec lo(kNu), hi(kNu);
    lo << w_lo, sigma_min;
    hi << w_hi, sigma_max;
    this->SetControlSet(ControlSet::Box(lo, hi));
    nominal_ = Vec(kNu);
    nominal_ << w_nominal, sigma_nominal;
  }

 private:
  const Derived& derived() const { return static_cast<const Derived&>(*this); }

  double eps_ = 1.0;
  Vec nominal_;
};

}  // namespace ocpb
