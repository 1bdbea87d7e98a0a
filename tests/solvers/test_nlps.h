// Small hand-written NLPs for the Ipopt and NLopt adapter tests.
#pragma once

#include <cmath>

#include "core/nlp.h"

namespace ocpb::testing {

/// Hock-Schittkowski problem 71 (Hock & Schittkowski, "Test examples for nonlinear programming
/// codes", 1981; Ipopt's hs071 example):
///   minimize    x0 x3 (x0 + x1 + x2) + x2
///   subject to  x0 x1 x2 x3 >= 25,  x0^2 + x1^2 + x2^2 + x3^2 = 40,  1 <= x <= 5,
/// start (1, 5, 5, 1); optimum x* = (1, 4.74299963, 3.82114998, 1.37940829), f* = 17.0140173,
/// multipliers (Lagrangian f + lambda^T g) lambda* = (-0.552293, 0.161469).
/// Exact Hessian; `fail_from` makes every evaluation with x0 > fail_from return false.
class Hs071 final : public Nlp {
 public:
  explicit Hs071(bool with_hessian = true, double fail_from = INFINITY)
      : with_hessian_(with_hessian), fail_from_(fail_from) {
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 4; ++c) {
        jac_rows_.push_back(r);
        jac_cols_.push_back(c);
      }
    }
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c <= r; ++c) {
        hess_rows_.push_back(r);
        hess_cols_.push_back(c);
      }
    }
  }
  int num_variables() const override { return 4; }
  int num_constraints() const override { return 2; }
  void Bounds(Vec* zl, Vec* zu, Vec* gl, Vec* gu) const override {
    *zl = Vec::Constant(4, 1.0);
    *zu = Vec::Constant(4, 5.0);
    *gl = Eigen::Vector2d(25.0, 40.0);
    *gu = Eigen::Vector2d(2e19, 40.0);
  }
  Vec StartingPoint() const override { return Eigen::Vector4d(1.0, 5.0, 5.0, 1.0); }
  bool Objective(ConstVecRef x, double* f) const override {
    *f = x[0] * x[3] * (x[0] + x[1] + x[2]) + x[2];
    return Ok(x);
  }
  bool Gradient(ConstVecRef x, VecRef g) const override {
    g[0] = x[3] * (2.0 * x[0] + x[1] + x[2]);
    g[1] = x[0] * x[3];
    g[2] = x[0] * x[3] + 1.0;
    g[3] = x[0] * (x[0] + x[1] + x[2]);
    return Ok(x);
  }
  bool Constraints(ConstVecRef x, VecRef g) const override {
    g[0] = x[0] * x[1] * x[2] * x[3];
    g[1] = x.squaredNorm();
    return Ok(x);
  }
  bool JacobianValues(ConstVecRef x, VecRef v) const override {
    v[0] = x[1] * x[2] * x[3];
    v[1] = x[0] * x[2] * x[3];
    v[2] = x[0] * x[1] * x[3];
    v[3] = x[0] * x[1] * x[2];
    for (int i = 0; i < 4; ++i) v[4 + i] = 2.0 * x[i];
    return Ok(x);
  }
  bool HasHessian() const override { return with_hessian_; }
  bool HessianValues(ConstVecRef x, double s, ConstVecRef l, VecRef v) const override {
    // Lower triangle row by row: (0,0) (1,0) (1,1) (2,0) (2,1) (2,2) (3,0) (3,1) (3,2) (3,3).
    v[0] = s * 2.0 * x[3] + 2.0 * l[1];
    v[1] = s * x[3] + l[0] * x[2] * x[3];
    v[2] = 2.0 * l[1];
    v[3] = s * x[3] + l[0] * x[1] * x[3];
    v[4] = l[0] * x[0] * x[3];
    v[5] = 2.0 * l[1];
    v[6] = s * (2.0 * x[0] + x[1] + x[2]) + l[0] * x[1] * x[2];
    v[7] = s * x[0] + l[0] * x[0] * x[2];
    v[8] = s * x[0] + l[0] * x[0] * x[1];
    v[9] = 2.0 * l[1];
    return Ok(x);
  }

 private:
  bool Ok(ConstVecRef x) const { return !(x[0] > fail_from_); }
  bool with_hessian_;
  double fail_from_;
};

/// Rosenbrock's function on the unit disc (inequality constraint only; the example of MATLAB's
/// fmincon documentation):
///   minimize (1 - x0)^2 + 100 (x1 - x0^2)^2  subject to  x0^2 + x1^2 <= 1,
/// start (-1, 0.5) (infeasible: |x|^2 = 1.25), optimum
/// x* = (0.7864, 0.6177), f* = 0.0456748. `radius2` changes the disc; `lower` adds x0 + x1 >= lower
/// (lower = 3 with radius2 = 1 makes the problem infeasible).
class RosenbrockDisc final : public Nlp {
 public:
  explicit RosenbrockDisc(double radius2 = 1.0, double lower = -INFINITY)
      : radius2_(radius2), lower_(lower) {
    const int m = num_constraints();
    for (int r = 0; r < m; ++r) {
      for (int c = 0; c < 2; ++c) {
        jac_rows_.push_back(r);
        jac_cols_.push_back(c);
      }
    }
    hess_rows_ = {0, 1, 1};
    hess_cols_ = {0, 0, 1};
  }
  int num_variables() const override { return 2; }
  int num_constraints() const override { return std::isfinite(lower_) ? 2 : 1; }
  void Bounds(Vec* zl, Vec* zu, Vec* gl, Vec* gu) const override {
    *zl = Vec::Constant(2, -INFINITY);
    *zu = Vec::Constant(2, INFINITY);
    *gl = Vec::Constant(num_constraints(), -INFINITY);
    *gu = Vec::Constant(num_constraints(), INFINITY);
    (*gu)[0] = radius2_;
    if (num_constraints() == 2) (*gl)[1] = lower_;
  }
  Vec StartingPoint() const override { return Eigen::Vector2d(-1.0, 0.5); }
  bool Objective(ConstVecRef x, double* f) const override {
    *f = (1.0 - x[0]) * (1.0 - x[0]) + 100.0 * std::pow(x[1] - x[0] * x[0], 2);
    return true;
  }
  bool Gradient(ConstVecRef x, VecRef g) const override {
    g[0] = -2.0 * (1.0 - x[0]) - 400.0 * x[0] * (x[1] - x[0] * x[0]);
    g[1] = 200.0 * (x[1] - x[0] * x[0]);
    return true;
  }
  bool Constraints(ConstVecRef x, VecRef g) const override {
    g[0] = x.squaredNorm();
    if (num_constraints() == 2) g[1] = x[0] + x[1];
    return true;
  }
  bool JacobianValues(ConstVecRef x, VecRef v) const override {
    v[0] = 2.0 * x[0];
    v[1] = 2.0 * x[1];
    if (num_constraints() == 2) v[2] = v[3] = 1.0;
    return true;
  }
  bool HasHessian() const override { return true; }
  bool HessianValues(ConstVecRef x, double s, ConstVecRef l, VecRef v) const override {
    v[0] = s * (2.0 - 400.0 * x[1] + 1200.0 * x[0] * x[0]) + 2.0 * l[0];
    v[1] = s * (-400.0 * x[0]);
    v[2] = s * 200.0 + 2.0 * l[0];
    return true;
  }

 private:
  double radius2_, lower_;
};

}  // namespace ocpb::testing
