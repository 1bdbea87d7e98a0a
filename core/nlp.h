// A backend-neutral sparse nonlinear program, the seam between transcriptions and NLP solvers.
#pragma once

#include <vector>

#include "core/types.h"

namespace ocpb {

/// minimize f(z)  subject to  g_l <= g(z) <= g_u,  z_l <= z <= z_u   (z in R^n, g in R^m).
///
/// Derivatives are sparse with a structure fixed at construction: the Jacobian of g as
/// (row, col) triplets, and the Hessian of the Lagrangian sigma f + lambda^T g as triplets of
/// its lower triangle (row >= col). Value arrays follow the triplet order. Equal bounds mean an
/// equality; +-inf (or |v| >= 1e19) means no bound.
///
/// Evaluations return false on a numerical failure (NaN/inf); solvers then report a status,
/// they never see an exception from here.
class Nlp {
 public:
  virtual ~Nlp() = default;

  virtual int num_variables() const = 0;
  virtual int num_constraints() const = 0;
  virtual void Bounds(Vec* z_lower, Vec* z_upper, Vec* g_lower, Vec* g_upper) const = 0;
  virtual Vec StartingPoint() const = 0;

  virtual bool Objective(ConstVecRef z, double* f) const = 0;
  virtual bool Gradient(ConstVecRef z, VecRef grad) const = 0;
  virtual bool Constraints(ConstVecRef z, VecRef g) const = 0;

  const std::vector<int>& jacobian_rows() const { return jac_rows_; }
  const std::vector<int>& jacobian_cols() const { return jac_cols_; }
  virtual bool JacobianValues(ConstVecRef z, VecRef values) const = 0;

  /// False when the NLP offers no exact Hessian (solvers then use a quasi-Newton one).
  virtual bool HasHessian() const { return false; }
  const std::vector<int>& hessian_rows() const { return hess_rows_; }
  const std::vector<int>& hessian_cols() const { return hess_cols_; }
  virtual bool HessianValues(ConstVecRef /*z*/,
                             double /*sigma*/,
                             ConstVecRef /*lambda*/,
                             VecRef /*values*/) const {
    return false;
  }

 protected:
  std::vector<int> jac_rows_, jac_cols_;
  std::vector<int> hess_rows_, hess_cols_;
};

/// A starting point for the multipliers of an Nlp, in the sign convention of Ipopt (and of
/// Nlp::HessianValues): at a KKT point sigma grad f + J^T lambda - z_lower + z_upper = 0, with
/// z_lower, z_upper >= 0 the multipliers of the variable bounds z >= z_l and z <= z_u (entries of
/// unbounded sides are ignored). All three empty: no starting multipliers (a cold start).
struct NlpMultipliers {
  Vec lambda;   ///< m entries, one per constraint row
  Vec z_lower;  ///< n entries
  Vec z_upper;  ///< n entries

  bool empty() const { return lambda.size() == 0 && z_lower.size() == 0 && z_upper.size() == 0; }
  /// True when the sizes fit an Nlp with n variables and m constraints and every entry is
  /// finite.
  bool Fits(int n, int m) const {
    return lambda.size() == m && z_lower.size() == n && z_upper.size() == n && lambda.allFinite() &&
           z_lower.allFinite() && z_upper.allFinite();
  }
};

}  // namespace ocpb
