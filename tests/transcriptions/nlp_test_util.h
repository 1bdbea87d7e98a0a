// Helpers for the transcription tests: dense views of sparse derivatives and a small
// Newton-KKT solver for equality-constrained NLPs (an independent reference, not a product).
#pragma once

#include <memory>
#include <string>

#include "core/nlp.h"
#include "transcriptions/transcription.h"

namespace ocpb::testing {

/// The constraint Jacobian (m x n) assembled from the triplets.
Mat DenseJacobian(const Nlp& nlp, const Vec& z);
/// The full symmetric Hessian of the Lagrangian (n x n) from the lower-triangle triplets.
Mat DenseHessian(const Nlp& nlp, const Vec& z, double sigma, const Vec& lambda);
/// sigma grad f + J^T lambda.
Vec LagrangianGradient(const Nlp& nlp, const Vec& z, double sigma, const Vec& lambda);

/// Newton's method on the KKT conditions of min f s.t. g(z) = g_l, for NLPs whose constraints
/// are all equalities and whose variable bounds are either equal (fixed variables) or infinite;
/// throws std::logic_error otherwise. Each step solves
///   [H_FF  J_F^T; J_F  0] [dz_F; lambda+] = -[grad_F f; g - g_l]
/// over the free variables F with a sparse LU. A QP converges in one step.
struct KktSolution {
  Vec z;
  Vec lambda;
  int iterations = 0;
  bool converged = false;
  double step_norm = -1.0;        ///< |dz|_inf of the last step
  double constraint_norm = -1.0;  ///< |g - g_l|_inf at z
};
KktSolution SolveEqualityKkt(const Nlp& nlp,
                             const Vec& z0,
                             int max_iterations = 30,
                             double tolerance = 1e-11);

/// Transcribes `ocp` with the registered-looking scheme name ("euler", "trapezoid",
/// "hermite-simpson", "lgr") without going through the solver registry.
std::unique_ptr<Transcription> MakeScheme(const std::string& name);

}  // namespace ocpb::testing
