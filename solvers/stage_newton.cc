#include "solvers/stage_newton.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "solvers/augmented_lagrangian_ocp.h"
#include "solvers/message_number.h"

namespace ocpb {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The reduced problem J(U) of a StageRkOcp with its stage weights and control set, and the sweeps.
class Reduced {
 public:
  Reduced(const StageRkOcp& srk, const ControlSet& controls) : srk_(srk), set_(controls) {
    const int s = srk.stages(), N = srk.intervals();
    weight_.resize(s * N);
    for (int k = 0; k < N; ++k) {
      for (int i = 0; i < s; ++i) weight_[k * s + i] = srk.StageWeight(k, i);
    }
  }

  double Value(const Mat& U) const { return srk_.Simulate(U, nullptr); }
  // J and dJ/dU; NaN when J is not finite (G is then unset).
  double Gradient(const Mat& U, Mat* G) {
    const double J = srk_.Simulate(U, &X_);
    if (!std::isfinite(J)) return kNaN;
    srk_.Adjoint(U, X_, &Lambda_, &Y_, &P_, G);
    return G->allFinite() ? J : kNaN;
  }
  // dJ/dU divided by the stage weights: H_u at every stage.
  Mat Scaled(const Mat& G) const { return G.array().rowwise() / weight_.transpose().array(); }
  void Project(Mat* U) const {
    for (int c = 0; c < U->cols(); ++c) set_.Project(U->col(c));
  }
  double Residual(const Mat& U, const Mat& G) const {
    Mat step = U - Scaled(G);
    Project(&step);
    return (U - step).lpNorm<Eigen::Infinity>();
  }
  const Vec& weight() const { return weight_; }
  const ControlSet& set() const { return set_; }

 private:
  const StageRkOcp& srk_;
  const ControlSet& set_;
  Vec weight_;
  Mat X_, Lambda_, Y_, P_;
};

// The directions the two-metric step holds at U (within eps of U's boundary): a box component
// at a bound that the scaled gradient S pushes through, and the radial direction of a ball block
// on its sphere that S pushes outwards. ProjectToFree removes them from a matrix of the controls'
// shape (per column an orthogonal projection, so it commutes with the per-column weights).
// AddSphereCurvature adds what the sphere's curvature gives the Hessian of the Lagrangian on a
// held ball's tangent space: with G = dJ/du = -lambda n on the sphere (lambda = -G.n > 0 there)
// and the constraint |u - c| - r <= 0 of Hessian (I - n n^T) / |u - c|, the term
// (lambda / |u - c|) P_T. Without it the tangent step of an H nearly linear in u has no
// curvature and runs far along the tangent.
class HeldDirections {
 public:
  HeldDirections(const ControlSet& set, const Mat& U, const Mat& G, const Mat& S, double eps)
      : free_(Mat::Ones(U.rows(), U.cols())) {
    for (int c = 0; c < U.cols(); ++c) {
      for (const ControlSet::Block& b : set.blocks()) {
        if (b.kind == ControlSet::Kind::kBox) {
          for (int i = 0; i < b.size; ++i) {
            const int r = b.offset + i;
            if ((U(r, c) - b.lower[i] <= eps && S(r, c) > 0.0) ||
                (b.upper[i] - U(r, c) <= eps && S(r, c) < 0.0)) {
              free_(r, c) = 0.0;
            }
          }
          continue;
        }
        Vec normal = U.col(c).segment(b.offset, b.size) - b.center;
        const double norm = normal.norm();
        if (norm > 0.0 && norm >= b.radius - eps) {
          normal /= norm;
          if (normal.dot(S.col(c).segment(b.offset, b.size)) < 0.0) {
            const double curvature = -normal.dot(G.col(c).segment(b.offset, b.size)) / norm;
            radial_.push_back({c, b.offset, normal, curvature});
          }
        }
      }
    }
  }

  Mat ProjectToFree(Mat V) const {
    V.array() *= free_.array();
    for (const Radial& r : radial_) {
      auto v = V.col(r.col).segment(r.offset, r.normal.size());
      const double along = r.normal.dot(v);
      v -= along * r.normal;
    }
    return V;
  }

  // Hp += the sphere's term for p in the free space (p's held blocks are tangent already).
  void AddSphereCurvature(const Mat& p, Mat* Hp) const {
    for (const Radial& r : radial_) {
      const int n = static_cast<int>(r.normal.size());
      Hp->col(r.col).segment(r.offset, n) += r.curvature * p.col(r.col).segment(r.offset, n);
    }
  }

 private:
  struct Radial {
    int col, offset;
    Vec normal;
    double curvature;  // lambda / |u - c| (> 0: held only when G pushes outwards)
  };
  Mat free_;
  std::vector<Radial> radial_;
};

double Dot(const Mat& a, const Mat& b) { return a.cwiseProduct(b).sum(); }

}  // namespace

double StageProjectedResidual(const StageRkOcp& srk, const ControlSet& controls, const Mat& U) {
  Reduced reduced(srk, controls);
  Mat G;
  if (!std::isfinite(reduced.Gradient(U, &G))) return kNaN;
  return reduced.Residual(U, G);
}

StageNewtonOutcome StageNewton(const StageRkOcp& srk,
                               const ControlSet& controls,
                               const StageNewtonOptions& options,
                               const CpuLimit& limit,
                               Mat* U) {
  Reduced reduced(srk, controls);
  StageNewtonOutcome out;
  reduced.Project(U);
  Mat G, Gp, Gm, Hp, Ut;
  const Vec& w = reduced.weight();
  int null_steps = 0;  // accepted steps in a row that did not lower J (at its rounding)
  auto stop = [&](const char* code, std::string why) {
    out.code = code;
    out.why = std::move(why);
    return out;
  };
  for (;;) {
    out.J = reduced.Gradient(*U, &G);
    if (!std::isfinite(out.J)) return stop("not_finite", "J or its gradient is not finite");
    out.residual = reduced.Residual(*U, G);
    if (out.residual <= options.tolerance) {
      out.converged = true;
      return stop("converged",
                  "projected residual " + MessageNumber(out.residual, 3) +
                      " <= " + MessageNumber(options.tolerance, 3) + " after " +
                      std::to_string(out.iterations) + " Newton steps");
    }
    if (out.iterations >= options.max_iterations) {
      return stop("max_iterations",
                  "reached max_iterations = " + std::to_string(options.max_iterations) +
                      " Newton steps (projected residual " + MessageNumber(out.residual, 3) + ")");
    }
    if (limit.Reached()) {
      return stop(
          "max_cpu_seconds",
          "reached max_cpu_seconds (projected residual " + MessageNumber(out.residual, 3) + ")");
    }
    // The two-metric split: the held directions take the scaled gradient step, the free ones
    // Newton's.
    const Mat S = reduced.Scaled(G);
    const HeldDirections held(reduced.set(), *U, G, S, std::min(1e-2, out.residual));
    const Mat active_step = held.ProjectToFree(S) - S;
    // Preconditioned CG on H_FF d = -G_F, M = diag(w).
    auto precondition = [&](const Mat& r) {
      return held.ProjectToFree(Mat(r.array().rowwise() / w.transpose().array()));
    };
    auto hessian_times = [&](const Mat& p) -> bool {
      const double t = 1e-5 * std::max(1.0, U->lpNorm<Eigen::Infinity>()) /
                       std::max(p.lpNorm<Eigen::Infinity>(), std::numeric_limits<double>::min());
      ++out.hessian_products;
      if (!std::isfinite(reduced.Gradient(*U + t * p, &Gp)) ||
          !std::isfinite(reduced.Gradient(*U - t * p, &Gm))) {
        return false;
      }
      Hp = held.ProjectToFree((Gp - Gm) / (2.0 * t));
      held.AddSphereCurvature(p, &Hp);
      return Hp.allFinite();
    };
    Mat d = Mat::Zero(U->rows(), U->cols());
    Mat res = -held.ProjectToFree(G);
    Mat z = precondition(res);
    Mat p = z;
    double rz = Dot(res, z);
    const double forcing = std::min(0.1, std::sqrt(out.residual));
    const double cg_stop = forcing * forcing * rz;
    for (int it = 0; it < options.max_cg_iterations && rz > 0.0; ++it) {
      if (limit.Reached()) break;  // reported at the line search's first check
      ++out.cg_iterations;
      if (!hessian_times(p)) break;
      const double pHp = Dot(p, Hp);
      if (!(pHp > 0.0)) break;  // negative curvature: keep the iterate so far
      const double alpha = rz / pHp;
      d += alpha * p;
      res -= alpha * Hp;
      z = precondition(res);
      const double rz_next = Dot(res, z);
      if (rz_next <= cg_stop) break;
      p = z + (rz_next / rz) * p;
      rz = rz_next;
    }
    const Mat scaled_gradient_step = -held.ProjectToFree(S);
    const bool newton_direction = !d.isZero(0.0);
    if (!newton_direction) d = scaled_gradient_step;
    // The projected Armijo search, first along Newton's direction, then (if that finds no
    // decrease, or is no descent direction) along the scaled gradient. Where the predicted
    // decrease is itself at J's rounding (close to the solution, where Newton's decrease is
    // quadratic in the residual) J may not decrease by more than its rounding.
    const double rounding = 16.0 * std::numeric_limits<double>::epsilon() * (1.0 + std::abs(out.J));
    bool accepted = false;
    for (const Mat* direction : {static_cast<const Mat*>(&d), &scaled_gradient_step}) {
      if (direction != &d && !newton_direction) break;  // the same direction again
      for (double step = 1.0; step >= options.min_step && !accepted; step *= options.backtrack) {
        if (limit.Reached()) {
          return stop("max_cpu_seconds",
                      "reached max_cpu_seconds in the line search of Newton step " +
                          std::to_string(out.iterations) + " (projected residual " +
                          MessageNumber(out.residual, 3) + ")");
        }
        Ut = *U + step * (*direction + active_step);
        reduced.Project(&Ut);
        const double decrease = Dot(G, Ut - *U);
        if (!(decrease < 0.0)) continue;  // the projection left no descent at this step
        const double Jt = reduced.Value(Ut);
        const double allowed = -decrease <= rounding ? rounding : 0.0;
        if (std::isfinite(Jt) && Jt <= out.J + options.sufficient_decrease * decrease + allowed) {
          accepted = true;
          null_steps = Jt < out.J ? 0 : null_steps + 1;
        }
      }
      if (accepted) break;
    }
    if (!accepted) {
      if (limit.Reached()) {
        return stop("max_cpu_seconds",
                    "reached max_cpu_seconds at Newton step " + std::to_string(out.iterations) +
                        " (projected residual " + MessageNumber(out.residual, 3) + ")");
      }
      return stop("line_search",
                  "no step >= " + MessageNumber(options.min_step, 3) +
                      " decreased J enough at Newton step " + std::to_string(out.iterations) +
                      " (projected residual " + MessageNumber(out.residual, 3) + ")");
    }
    *U = Ut;
    ++out.iterations;
    if (null_steps >= 3) {
      return stop("rounding",
                  "J did not decrease over 3 Newton steps in a row (at its rounding; projected "
                  "residual " +
                      MessageNumber(out.residual, 3) + ")");
    }
  }
}

StageAugmentedLagrangianOutcome SingleSolveOutcome(const StageNewtonOutcome& solve) {
  StageAugmentedLagrangianOutcome out;
  out.last = solve;
  out.newton_iterations = solve.iterations;
  out.hessian_products = solve.hessian_products;
  out.cg_iterations = solve.cg_iterations;
  out.converged = solve.converged;
  out.code = solve.code;
  out.why = solve.why;
  return out;
}

StageAugmentedLagrangianOutcome StageNewtonAugmentedLagrangian(const StageRkOcp& srk,
                                                               AugmentedLagrangianOcp* al,
                                                               const ControlSet& controls,
                                                               const StageNewtonOptions& options,
                                                               double initial_penalty,
                                                               double penalty_growth,
                                                               double max_penalty,
                                                               double feasibility_tolerance,
                                                               int max_outer_iterations,
                                                               const CpuLimit& limit,
                                                               Mat* U) {
  StageAugmentedLagrangianOutcome out;
  const Ocp& problem = al->inner();
  const int N = srk.intervals();
  Vec nu = Vec::Zero(problem.num_terminal());
  double rho = initial_penalty;
  double previous = std::numeric_limits<double>::infinity();
  Mat X;
  Vec psi(problem.num_terminal());
  while (out.outer_iterations < max_outer_iterations) {
    al->SetTerminal(nu, rho);
    out.last = StageNewton(srk, controls, options, limit, U);
    ++out.outer_iterations;
    out.newton_iterations += out.last.iterations;
    out.hessian_products += out.last.hessian_products;
    out.cg_iterations += out.last.cg_iterations;
    if (!std::isfinite(srk.Simulate(*U, &X))) {
      out.code = "not_finite";
      out.why = "inner solve " + std::to_string(out.outer_iterations) + ": J is not finite";
      return out;
    }
    problem.TerminalConstraints(X.col(N), psi);
    out.terminal_residual = problem.num_terminal() > 0 ? psi.lpNorm<Eigen::Infinity>() : 0.0;
    // The multipliers the first-order update gives at this iterate; al keeps nu, rho of the
    // solve just made (its adjoint at U then has lambda_N = grad phi + psi_x^T (nu + rho psi)).
    out.multipliers = al->TerminalUpdate(X.col(N));
    if (!out.last.converged) {
      out.code = out.last.code;
      out.why = "inner solve " + std::to_string(out.outer_iterations) + ": " + out.last.why +
                "; terminal residual " + MessageNumber(out.terminal_residual, 3);
      return out;
    }
    if (out.terminal_residual <= feasibility_tolerance) {
      out.converged = true;
      out.code = "converged";
      out.why = "terminal residual " + MessageNumber(out.terminal_residual, 3) +
                " <= " + MessageNumber(feasibility_tolerance, 3) + ", projected residual " +
                MessageNumber(out.last.residual, 3) + " after " +
                std::to_string(out.outer_iterations) + " outer iterations (" +
                std::to_string(out.newton_iterations) + " Newton steps)";
      return out;
    }
    nu = out.multipliers;
    if (out.terminal_residual > 0.25 * previous) rho = std::min(rho * penalty_growth, max_penalty);
    previous = out.terminal_residual;
  }
  out.code = "max_outer_iterations";
  out.why = "reached max_outer_iterations = " + std::to_string(max_outer_iterations) +
            " (terminal residual " + MessageNumber(out.terminal_residual, 3) + ")";
  return out;
}

}  // namespace ocpb
