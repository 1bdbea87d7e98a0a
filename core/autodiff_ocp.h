// AutoDiffOcp: write a problem once, as templates on the scalar type, and get every
// first and second derivative the Ocp interface asks for by forward-mode AD (core/jet.h).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

#include "core/jet.h"
#include "core/ocp.h"

namespace ocpb {

/// CRTP base. `Derived` provides, for T in {double, Jet1<.>, Jet2<.>}:
///
///   template <class T> void EvalDynamics(double t, const VecT<T, NX>& x, const VecT<T, NU>& u,
///                                        VecT<T, NX>* f) const;
///   template <class T> T EvalRunningCost(double t, const VecT<T, NX>& x,
///                                        const VecT<T, NU>& u) const;        // optional
///   template <class T> T EvalTerminalCost(const VecT<T, NX>& x) const;            // optional
///   template <class T> T EvalInitialCost(const VecT<T, NX>& x0) const;            // optional
///   template <class T> void EvalBoundaryConstraints(const VecT<T, NX>& x0,
///                                                   const VecT<T, NX>& xf,
///                                                   VecT<T, Eigen::Dynamic>* b) const;
///                     // with Ocp::SetBoundaryConstraints (b arrives sized num_boundary())
///   template <class T> void EvalTerminalConstraints(const VecT<T, NX>& x,
///                                                   VecT<T, NPSI>* psi) const;   // if NPSI > 0
///   template <class T> void EvalPathConstraints(double t, const VecT<T, NX>& x,
///                                               const VecT<T, NU>& u,
///                                               VecT<T, NC>* c) const;         // if NC > 0
///
/// Derivatives with respect to z = (x, u) use Jet1<NX+NU> (first order) and
/// Jet2<NX+NU> (Hessians); terminal functions use Jet1<NX> / Jet2<NX>.
/// A problem may still override any virtual with hand-written derivatives.
///
/// Mayer problems: a problem that declares no EvalRunningCost has L = 0 (DefinesRunningCost()
/// is false): RunningCost returns 0, RunningCostGradient zeros, PointHessian skips the AD pass
/// over L, and RunningCostLowerBound is 0. The test is at compile time, on the name: a Derived
/// that declares EvalRunningCost (itself or in a base between it and AutoDiffOcp) has it called
/// by the same code as before, in any form: a private or ill-formed one still fails to compile
/// rather than becoming L = 0. Only a Derived that declares none gets L = 0 (so a misspelt name
/// means no running cost, as a misspelt EvalTerminalCost means phi = 0).
///
/// Dimensions are stated once, by the template arguments: the constructor sets nx = NX, nu = NU,
/// npsi = NPSI, nc = NC (with Ocp::SetDimensions' defaults for x0, weights and U), so a problem
/// need not call SetDimensions. One that does must repeat the same four numbers: any other value
/// throws std::invalid_argument naming the dimension, and the call changes nothing (x0, weights
/// and U set before it are kept).
template <class Derived, int NX, int NU, int NPSI = 0, int NC = 0>
class AutoDiffOcp : public Ocp {
 public:
  static_assert(
      NX >= 1 && NU >= 1 && NPSI >= 0 && NC >= 0,
      "AutoDiffOcp<Derived, NX, NU, NPSI, NC> needs NX >= 1, NU >= 1, NPSI >= 0, NC >= 0");
  static constexpr int kNz = NX + NU;
  using Z1 = Jet1<kNz>;
  using Z2 = Jet2<kNz>;
  using X1 = Jet1<NX>;
  using X2 = Jet2<NX>;

  AutoDiffOcp() { Ocp::SetDimensions(NX, NU, NPSI, NC); }

  // Defaults for the optional pieces.
  template <class T>
  T EvalTerminalCost(const VecT<T, NX>&) const {
    return T(0.0);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, NX>&, VecT<T, NPSI>*) const {
    static_assert(NPSI == 0, "a problem with NPSI > 0 must define EvalTerminalConstraints");
  }
  template <class T>
  void EvalPathConstraints(double, const VecT<T, NX>&, const VecT<T, NU>&, VecT<T, NC>*) const {
    static_assert(NC == 0, "a problem with NC > 0 must define EvalPathConstraints");
  }

  /// False when Derived declares no EvalRunningCost (a Mayer problem: L = 0). The base's
  /// EvalRunningCost(NoRunningCost) is found by name lookup only when Derived declares none
  /// of its own, which hides it whatever its signature or access.
  static constexpr bool DefinesRunningCost() {
    return !requires { Derived::EvalRunningCost(NoRunningCost{}); };
  }

  /// True when Derived declares EvalInitialCost (phi0(x(t0)), for a free initial state); found
  /// by name as DefinesRunningCost is.
  static constexpr bool DefinesInitialCost() {
    return !requires { Derived::EvalInitialCost(NoInitialCost{}); };
  }

  /// True when Derived declares EvalBoundaryConstraints (found by name, as above).
  static constexpr bool DefinesBoundaryConstraints() {
    return !requires { Derived::EvalBoundaryConstraints(NoBoundaryConstraints{}); };
  }
  using B1 = Jet1<2 * NX>;  // derivatives with respect to (x(t0), x(tf))
  using B2 = Jet2<2 * NX>;

  // ---- boundary constraints --------------------------------------------------------
  void BoundaryConstraints(ConstVecRef x0, ConstVecRef xf, VecRef b) const override {
    if constexpr (DefinesBoundaryConstraints()) {
      VecT<double, Eigen::Dynamic> out(num_boundary());
      self().EvalBoundaryConstraints(VecT<double, NX>(x0), VecT<double, NX>(xf), &out);
      CopyTo(out, b);
    } else {
      Ocp::BoundaryConstraints(x0, xf, b);
    }
  }
  void BoundaryConstraintsJacobian(
      ConstVecRef x0, ConstVecRef xf, VecRef b, MatRef b_x0, MatRef b_xf) const override {
    if constexpr (DefinesBoundaryConstraints()) {
      VecT<B1, NX> s0, sf;
      SeedEnds(x0, xf, &s0, &sf);
      VecT<B1, Eigen::Dynamic> out(num_boundary());
      self().EvalBoundaryConstraints(s0, sf, &out);
      for (int i = 0; i < num_boundary(); ++i) {
        b[i] = out[i].a;
        for (int j = 0; j < NX; ++j) {
          b_x0(i, j) = out[i].g[j];
          b_xf(i, j) = out[i].g[NX + j];
        }
      }
    } else {
      Ocp::BoundaryConstraintsJacobian(x0, xf, b, b_x0, b_xf);
    }
  }
  void BoundaryHessian(ConstVecRef x0, ConstVecRef xf, ConstVecRef mu, MatRef hess) const override {
    if constexpr (DefinesBoundaryConstraints()) {
      VecT<B2, NX> s0, sf;
      SeedEnds(x0, xf, &s0, &sf);
      VecT<B2, Eigen::Dynamic> out(num_boundary());
      self().EvalBoundaryConstraints(s0, sf, &out);
      Eigen::Matrix<double, 2 * NX, 2 * NX> h = Eigen::Matrix<double, 2 * NX, 2 * NX>::Zero();
      for (int i = 0; i < num_boundary(); ++i) h += mu[i] * out[i].h;
      CopyTo(h, hess);
    } else {
      Ocp::BoundaryHessian(x0, xf, mu, hess);
    }
  }

  // ---- values -------------------------------------------------------------------
  bool HasInitialCost() const override { return DefinesInitialCost(); }
  double InitialCost(ConstVecRef x0) const override {
    if constexpr (DefinesInitialCost()) {
      return self().EvalInitialCost(VecT<double, NX>(x0));
    } else {
      return 0.0;
    }
  }
  void InitialCostGradient(ConstVecRef x0, double* phi0, VecRef grad) const override {
    if constexpr (DefinesInitialCost()) {
      const X1 out = self().EvalInitialCost(SeedX<X1>(x0));
      *phi0 = out.a;
      for (int i = 0; i < NX; ++i) grad[i] = out.g[i];
    } else {
      *phi0 = 0.0;
      for (int i = 0; i < NX; ++i) grad[i] = 0.0;
    }
  }
  void InitialCostHessian(ConstVecRef x0, double sigma, MatRef hess) const override {
    Eigen::Matrix<double, NX, NX> h = Eigen::Matrix<double, NX, NX>::Zero();
    if constexpr (DefinesInitialCost()) {
      if (sigma != 0.0) h += sigma * self().EvalInitialCost(SeedX<X2>(x0)).h;
    }
    CopyTo(h, hess);
  }
  void Dynamics(double t, ConstVecRef x, ConstVecRef u, VecRef f) const override {
    VecT<double, NX> fx;
    self().EvalDynamics(t, VecT<double, NX>(x), VecT<double, NU>(u), &fx);
    CopyTo(fx, f);
  }
  double RunningCost(double t, ConstVecRef x, ConstVecRef u) const override {
    if constexpr (DefinesRunningCost()) {
      return self().EvalRunningCost(t, VecT<double, NX>(x), VecT<double, NU>(u));
    } else {
      return 0.0;
    }
  }
  double TerminalCost(ConstVecRef x) const override {
    return self().EvalTerminalCost(VecT<double, NX>(x));
  }
  void TerminalConstraints(ConstVecRef x, VecRef psi) const override {
    if constexpr (NPSI > 0) {
      VecT<double, NPSI> out;
      self().EvalTerminalConstraints(VecT<double, NX>(x), &out);
      CopyTo(out, psi);
    }
  }
  void PathConstraints(double t, ConstVecRef x, ConstVecRef u, VecRef c) const override {
    if constexpr (NC > 0) {
      VecT<double, NC> out;
      self().EvalPathConstraints(t, VecT<double, NX>(x), VecT<double, NU>(u), &out);
      CopyTo(out, c);
    }
  }

  // ---- first derivatives ---------------------------------------------------------
  void DynamicsJacobian(
      double t, ConstVecRef x, ConstVecRef u, VecRef f, MatRef fx, MatRef fu) const override {
    VecT<Z1, NX> xz;
    VecT<Z1, NU> uz;
    Seed(x, u, &xz, &uz);
    VecT<Z1, NX> out;
    self().EvalDynamics(t, xz, uz, &out);
    for (int i = 0; i < NX; ++i) {
      f[i] = out[i].a;
      fx.row(i) = out[i].g.template head<NX>().transpose();
      fu.row(i) = out[i].g.template tail<NU>().transpose();
    }
  }
  void RunningCostGradient(
      double t, ConstVecRef x, ConstVecRef u, double* L, VecRef Lx, VecRef Lu) const override {
    if constexpr (DefinesRunningCost()) {
      VecT<Z1, NX> xz;
      VecT<Z1, NU> uz;
      Seed(x, u, &xz, &uz);
      const Z1 out = self().EvalRunningCost(t, xz, uz);
      *L = out.a;
      Lx = out.g.template head<NX>();
      Lu = out.g.template tail<NU>();
    } else {
      *L = 0.0;  // element by element: GCC 12 warns falsely on setZero of a size-1 Ref
      for (int i = 0; i < NX; ++i) Lx[i] = 0.0;
      for (int j = 0; j < NU; ++j) Lu[j] = 0.0;
    }
  }
  void TerminalCostGradient(ConstVecRef x, double* phi, VecRef phix) const override {
    const X1 out = self().EvalTerminalCost(SeedX<X1>(x));
    *phi = out.a;
    phix = out.g;
  }
  void TerminalConstraintsJacobian(ConstVecRef x, VecRef psi, MatRef psix) const override {
    if constexpr (NPSI > 0) {
      VecT<X1, NPSI> out;
      self().EvalTerminalConstraints(SeedX<X1>(x), &out);
      for (int i = 0; i < NPSI; ++i) {
        psi[i] = out[i].a;
        psix.row(i) = out[i].g.transpose();
      }
    }
  }
  void PathConstraintsJacobian(
      double t, ConstVecRef x, ConstVecRef u, VecRef c, MatRef cx, MatRef cu) const override {
    if constexpr (NC > 0) {
      VecT<Z1, NX> xz;
      VecT<Z1, NU> uz;
      Seed(x, u, &xz, &uz);
      VecT<Z1, NC> out;
      self().EvalPathConstraints(t, xz, uz, &out);
      for (int i = 0; i < NC; ++i) {
        c[i] = out[i].a;
        cx.row(i) = out[i].g.template head<NX>().transpose();
        cu.row(i) = out[i].g.template tail<NU>().transpose();
      }
    }
  }

  // ---- second derivatives -------------------------------------------------------
  void PointHessian(double t,
                    ConstVecRef x,
                    ConstVecRef u,
                    double sigma,
                    ConstVecRef lambda,
                    ConstVecRef mu,
                    MatRef hess) const override {
    VecT<Z2, NX> xz;
    VecT<Z2, NU> uz;
    Seed(x, u, &xz, &uz);
    Eigen::Matrix<double, kNz, kNz> h = Eigen::Matrix<double, kNz, kNz>::Zero();
    if constexpr (DefinesRunningCost()) {
      if (sigma != 0.0) h += sigma * self().EvalRunningCost(t, xz, uz).h;
    }
    // Affine dynamics (Ocp::HasAffineDynamics) have f'' = 0: the Jet2 pass over f is skipped.
    if (lambda.size() > 0 && lambda.any() && !self().HasAffineDynamics()) {
      VecT<Z2, NX> f;
      self().EvalDynamics(t, xz, uz, &f);
      for (int i = 0; i < NX; ++i) h += lambda[i] * f[i].h;
    }
    if constexpr (NC > 0) {
      if (mu.size() > 0 && mu.any()) {
        VecT<Z2, NC> c;
        self().EvalPathConstraints(t, xz, uz, &c);
        for (int i = 0; i < NC; ++i) h += mu[i] * c[i].h;
      }
    }
    CopyTo(h, hess);
  }
  void TerminalHessian(ConstVecRef x, double sigma, ConstVecRef nu, MatRef hess) const override {
    const VecT<X2, NX> xs = SeedX<X2>(x);
    Eigen::Matrix<double, NX, NX> h = Eigen::Matrix<double, NX, NX>::Zero();
    if (sigma != 0.0) h += sigma * self().EvalTerminalCost(xs).h;
    if constexpr (NPSI > 0) {
      VecT<X2, NPSI> psi;
      self().EvalTerminalConstraints(xs, &psi);
      for (int i = 0; i < NPSI; ++i) h += nu[i] * psi[i].h;
    }
    CopyTo(h, hess);
  }

  /// L = 0 is a lower bound of a Mayer problem's running cost; a problem with a running cost
  /// gets Ocp's answer (none) unless it overrides this itself.
  std::optional<double> RunningCostLowerBound() const override {
    if constexpr (DefinesRunningCost()) {
      return Ocp::RunningCostLowerBound();
    } else {
      return 0.0;
    }
  }

 protected:
  /// Checks (nx, nu, npsi, nc) against the template arguments, which already set them: a
  /// second statement of the dimensions may only agree with the first.
  void SetDimensions(int nx, int nu, int npsi, int nc) {
    CheckDimension("nx", nx, NX);
    CheckDimension("nu", nu, NU);
    CheckDimension("npsi", npsi, NPSI);
    CheckDimension("nc", nc, NC);
  }

 private:
  // The default of the optional running cost: a name that only a Derived without its own
  // EvalRunningCost inherits (see DefinesRunningCost); declared, never defined or called.
  struct NoRunningCost {};
  static void EvalRunningCost(NoRunningCost);
  struct NoInitialCost {};
  static void EvalInitialCost(NoInitialCost);
  struct NoBoundaryConstraints {};
  static void EvalBoundaryConstraints(NoBoundaryConstraints);

  void CheckDimension(const char* what, int given, int declared) const {
    if (given != declared) {
      throw std::invalid_argument("problem dimensions: SetDimensions gives " + std::string(what) +
                                  " = " + std::to_string(given) + " but AutoDiffOcp's template " +
                                  "argument says " + std::to_string(declared) +
                                  " (state the dimensions once, as template arguments)");
    }
  }

  // Element-wise copies: GCC 12 warns (falsely, -Warray-bounds) on Eigen's vectorized copy of
  // small fixed-size matrices into a Ref (1x1 at -O2; 3-vectors with AVX, -march=x86-64-v3),
  // which -Werror would turn into a build failure.
  template <class Fixed>
  static void CopyTo(const Fixed& from, MatRef to) {
    for (int j = 0; j < from.cols(); ++j) {
      for (int i = 0; i < from.rows(); ++i) to(i, j) = from(i, j);
    }
  }
  template <class Fixed>
  static void CopyTo(const Fixed& from, VecRef to) {
    for (int i = 0; i < from.size(); ++i) to[i] = from[i];
  }

  const Derived& self() const { return static_cast<const Derived&>(*this); }

  template <class J>
  static void Seed(ConstVecRef x, ConstVecRef u, VecT<J, NX>* xz, VecT<J, NU>* uz) {
    for (int i = 0; i < NX; ++i) (*xz)[i] = J::Variable(x[i], i);
    for (int j = 0; j < NU; ++j) (*uz)[j] = J::Variable(u[j], NX + j);
  }
  template <class J>
  static void SeedEnds(ConstVecRef x0, ConstVecRef xf, VecT<J, NX>* s0, VecT<J, NX>* sf) {
    for (int i = 0; i < NX; ++i) {
      (*s0)[i] = J::Variable(x0[i], i);
      (*sf)[i] = J::Variable(xf[i], NX + i);
    }
  }
  template <class J>
  static VecT<J, NX> SeedX(ConstVecRef x) {
    VecT<J, NX> xs;
    for (int i = 0; i < NX; ++i) xs[i] = J::Variable(x[i], i);
    return xs;
  }
};

}  // namespace ocpb
