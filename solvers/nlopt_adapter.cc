#include "solvers/nlopt_adapter.h"

#include <nlopt.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <sstream>
#include <stdexcept>

#include "core/option_binding.h"
#include "core/timer.h"
#include "solvers/nlp_stationarity.h"

namespace ocpb {
namespace {

constexpr double kNoBound = 1e19;  // core/nlp.h: |v| >= 1e19 means no bound

struct AlgorithmInfo {
  const char* name;
  nlopt::algorithm algorithm;
  bool equalities;    // takes equality constraints itself
  bool inequalities;  // takes inequality constraints itself
};

const std::vector<AlgorithmInfo>& Algorithms() {
  static const std::vector<AlgorithmInfo> list = {
      {"LD_SLSQP", nlopt::LD_SLSQP, true, true},
      {"LD_MMA", nlopt::LD_MMA, false, true},
      {"LD_CCSAQ", nlopt::LD_CCSAQ, false, true},
      {"LD_LBFGS", nlopt::LD_LBFGS, false, false},
      {"AUGLAG", nlopt::AUGLAG, true, true},
      {"AUGLAG_EQ", nlopt::AUGLAG_EQ, true, true},
  };
  return list;
}

const AlgorithmInfo* FindAlgorithm(const std::string& name) {
  for (const AlgorithmInfo& a : Algorithms()) {
    if (name == a.name) return &a;
  }
  return nullptr;
}

bool IsAuglag(const std::string& name) { return name == "AUGLAG" || name == "AUGLAG_EQ"; }

// The NLP as NLopt sees it: constraint rows split into equalities and one-sided inequalities,
// one-entry caches for g and the Jacobian (NLopt evaluates both constraint functions and the
// objective at the same point), and the evaluation history.
class NloptProblem {
 public:
  NloptProblem(const Nlp& nlp, const NloptOptions& options)
      : nlp_(nlp), options_(options), n_(nlp.num_variables()), m_(nlp.num_constraints()) {
    nlp.Bounds(&zl_, &zu_, &gl_, &gu_);
    eq_of_row_.assign(m_, -1);
    upper_of_row_.assign(m_, -1);
    lower_of_row_.assign(m_, -1);
    for (int r = 0; r < m_; ++r) {
      const bool has_lo = gl_[r] > -kNoBound, has_hi = gu_[r] < kNoBound;
      if (has_lo && has_hi && gl_[r] == gu_[r]) {
        eq_of_row_[r] = num_eq_++;
        eq_rows_.push_back(r);
        continue;
      }
      if (has_hi) {
        upper_of_row_[r] = num_ineq_++;
        ineq_rows_.push_back({r, +1});
      }
      if (has_lo) {
        lower_of_row_[r] = num_ineq_++;
        ineq_rows_.push_back({r, -1});
      }
    }
  }

  int n() const { return n_; }
  int num_eq() const { return num_eq_; }
  int num_ineq() const { return num_ineq_; }
  const Vec& z_lower() const { return zl_; }
  const Vec& z_upper() const { return zu_; }
  bool evaluation_failed() const { return failed_; }
  const std::string& failure() const { return failure_; }
  std::vector<IterationRecord>& history() { return history_; }
  int evaluations() const { return evaluations_; }
  const Vec& last_good_z() const { return last_good_z_; }

  static double Objective(unsigned n, const double* x, double* grad, void* data) {
    auto* self = static_cast<NloptProblem*>(data);
    const Eigen::Map<const Vec> z(x, n);
    double f = NAN;
    self->Guard("Objective", [&] { return self->nlp_.Objective(z, &f) && std::isfinite(f); });
    if (grad != nullptr) {
      Eigen::Map<Vec> g(grad, n);
      self->Guard("Gradient", [&] { return self->nlp_.Gradient(z, g) && g.allFinite(); });
    }
    ++self->evaluations_;
    self->last_good_z_ = z;
    self->last_objective_z_ = z;
    if (self->options_.record_history) {
      IterationRecord r;
      r.iteration = self->evaluations_;
      r.J = f;
      r.primal_inf = self->m_ == 0 ? self->BoundViolation(z) : NAN;
      r.cpu_seconds = self->watch_.cpu();
      self->history_.push_back(r);
    }
    return f;
  }

  static void Equalities(
      unsigned m, double* result, unsigned n, const double* x, double* grad, void* data) {
    auto* self = static_cast<NloptProblem*>(data);
    const Eigen::Map<const Vec> z(x, n);
    self->PrepareValues(z);
    for (int e = 0; e < self->num_eq_; ++e) {
      const int r = self->eq_rows_[e];
      result[e] = self->g_[r] - self->gl_[r];
    }
    if (grad != nullptr) {
      self->PrepareJacobian(z);
      std::fill(grad, grad + static_cast<size_t>(m) * n, 0.0);
      const auto& rows = self->nlp_.jacobian_rows();
      const auto& cols = self->nlp_.jacobian_cols();
      for (size_t k = 0; k < rows.size(); ++k) {
        const int e = self->eq_of_row_[rows[k]];
        if (e >= 0) grad[static_cast<size_t>(e) * n + cols[k]] += self->jac_[k];
      }
    }
  }

  static void Inequalities(
      unsigned m, double* result, unsigned n, const double* x, double* grad, void* data) {
    auto* self = static_cast<NloptProblem*>(data);
    const Eigen::Map<const Vec> z(x, n);
    self->PrepareValues(z);
    for (int i = 0; i < self->num_ineq_; ++i) {
      const auto [r, sign] = self->ineq_rows_[i];
      result[i] = sign > 0 ? self->g_[r] - self->gu_[r] : self->gl_[r] - self->g_[r];
    }
    if (grad != nullptr) {
      self->PrepareJacobian(z);
      std::fill(grad, grad + static_cast<size_t>(m) * n, 0.0);
      const auto& rows = self->nlp_.jacobian_rows();
      const auto& cols = self->nlp_.jacobian_cols();
      for (size_t k = 0; k < rows.size(); ++k) {
        const int hi = self->upper_of_row_[rows[k]], lo = self->lower_of_row_[rows[k]];
        if (hi >= 0) grad[static_cast<size_t>(hi) * n + cols[k]] += self->jac_[k];
        if (lo >= 0) grad[static_cast<size_t>(lo) * n + cols[k]] -= self->jac_[k];
      }
    }
  }

 private:
  template <class Fn>
  void Guard(const char* what, Fn&& fn) {
    bool ok = false;
    try {
      ok = fn();
    } catch (const std::exception& e) {
      failure_ = std::string("Nlp::") + what + " threw: " + e.what();
    }
    if (!ok) {
      if (failure_.empty()) {
        failure_ = std::string("Nlp::") + what + " failed (NaN/inf) at evaluation " +
                   std::to_string(evaluations_ + 1);
      }
      failed_ = true;
      throw nlopt::forced_stop();
    }
  }

  double BoundViolation(ConstVecRef z) const {
    double worst = 0.0;
    for (int i = 0; i < n_; ++i) worst = std::max({worst, zl_[i] - z[i], z[i] - zu_[i]});
    return worst;
  }

  void PrepareValues(ConstVecRef z) {
    if (g_valid_ && g_z_ == z) return;
    g_valid_ = false;
    g_.resize(m_);
    Guard("Constraints", [&] { return nlp_.Constraints(z, g_) && g_.allFinite(); });
    g_z_ = z;
    g_valid_ = true;
    // The history row of the objective evaluation at this point gets its violation.
    if (options_.record_history && !history_.empty() && last_objective_z_.size() == z.size() &&
        last_objective_z_ == z) {
      double worst = BoundViolation(z);
      for (int r = 0; r < m_; ++r) worst = std::max({worst, gl_[r] - g_[r], g_[r] - gu_[r]});
      history_.back().primal_inf = worst;
    }
  }

  void PrepareJacobian(ConstVecRef z) {
    if (jac_valid_ && jac_z_ == z) return;
    jac_valid_ = false;
    jac_.resize(static_cast<Eigen::Index>(nlp_.jacobian_rows().size()));
    Guard("JacobianValues", [&] { return nlp_.JacobianValues(z, jac_) && jac_.allFinite(); });
    jac_z_ = z;
    jac_valid_ = true;
  }

  const Nlp& nlp_;
  const NloptOptions& options_;
  const int n_, m_;
  Vec zl_, zu_, gl_, gu_;
  std::vector<int> eq_of_row_, upper_of_row_, lower_of_row_;
  std::vector<int> eq_rows_;
  std::vector<std::pair<int, int>> ineq_rows_;  // (row, +1: g - g_u; -1: g_l - g)
  int num_eq_ = 0, num_ineq_ = 0;
  Vec g_z_, g_, jac_z_, jac_;
  bool g_valid_ = false, jac_valid_ = false;
  Vec last_objective_z_, last_good_z_;
  bool failed_ = false;
  std::string failure_;
  int evaluations_ = 0;
  std::vector<IterationRecord> history_;
  Stopwatch watch_;
};

// Why `options.algorithm` cannot run on this NLP, or "" when it can.
std::string Refusal(const NloptOptions& o, int n, int num_eq, int num_ineq) {
  const AlgorithmInfo& a = *FindAlgorithm(o.algorithm);
  const std::string sizes = " (n = " + std::to_string(n) +
                            ", equalities = " + std::to_string(num_eq) +
                            ", inequalities = " + std::to_string(num_ineq) + ")";
  if (num_eq > 0 && !a.equalities) {
    return o.algorithm + " takes no equality constraints; use LD_SLSQP, AUGLAG or AUGLAG_EQ" +
           sizes;
  }
  if (num_ineq > 0 && !a.inequalities) {
    return o.algorithm + " takes only bound constraints; use LD_SLSQP, LD_MMA, LD_CCSAQ or AUGLAG" +
           sizes;
  }
  const double dense = static_cast<double>(num_eq + num_ineq) * n;
  if (dense > o.max_dense_jacobian) {
    return "the dense constraint Jacobian has m * n = " + std::to_string(dense) +
           " entries > max_dense_jacobian = " + std::to_string(o.max_dense_jacobian) + sizes;
  }
  // Where the dense quasi-Newton / subproblem work happens.
  const bool local_sees_ineq = o.algorithm == "AUGLAG_EQ" && num_ineq > 0;
  std::string dense_alg = o.algorithm;
  if (IsAuglag(o.algorithm)) dense_alg = o.local_algorithm;
  if (o.algorithm == "AUGLAG_EQ" && num_ineq > 0 &&
      !FindAlgorithm(o.local_algorithm)->inequalities) {
    return "AUGLAG_EQ passes the inequality constraints to its local algorithm " +
           o.local_algorithm +
           ", which takes none; use local_algorithm=LD_MMA, LD_CCSAQ or LD_SLSQP, or AUGLAG" +
           sizes;
  }
  if (dense_alg == "LD_SLSQP" && n > o.slsqp_max_variables) {
    return "LD_SLSQP works with dense n x n matrices (O(n^2) memory, O(n^3) per iteration): n = " +
           std::to_string(n) + " > slsqp_max_variables = " + std::to_string(o.slsqp_max_variables);
  }
  const int mma_ineq = IsAuglag(o.algorithm) ? (local_sees_ineq ? num_ineq : 0) : num_ineq;
  if ((dense_alg == "LD_MMA" || dense_alg == "LD_CCSAQ") && mma_ineq > o.mma_max_inequalities) {
    return dense_alg + "'s dual subproblem is dense in the inequality constraints: " +
           std::to_string(mma_ineq) +
           " > mma_max_inequalities = " + std::to_string(o.mma_max_inequalities);
  }
  return "";
}

}  // namespace

std::vector<std::string> NloptAlgorithmNames() {
  std::vector<std::string> names;
  for (const AlgorithmInfo& a : Algorithms()) names.push_back(a.name);
  return names;
}

namespace {

std::vector<std::string> LocalAlgorithmNames() {
  std::vector<std::string> names;
  for (const std::string& n : NloptAlgorithmNames()) {
    if (!IsAuglag(n)) names.push_back(n);
  }
  return names;
}

const OptionBinding<NloptOptions>& NloptBinding() {
  static const OptionBinding<NloptOptions> table = [] {
    using O = NloptOptions;
    OptionBinding<O> t("nlopt");
    t.Text("algorithm",
           &O::algorithm,
           "the NLopt algorithm (also --algorithm)",
           NloptAlgorithmNames());
    t.Text("local_algorithm",
           &O::local_algorithm,
           "AUGLAG / AUGLAG_EQ's subsidiary algorithm",
           LocalAlgorithmNames());
    const std::string disables = " (<= 0 disables the test)";
    t.Number(
        "ftol_rel", &O::ftol_rel, "stop when f changes by less than this times |f|" + disables);
    t.Number("xtol_rel", &O::xtol_rel, "stop when every z_i changes by less than this" + disables);
    t.Integer("maxeval", &O::maxeval, "objective evaluations at most", OptionBounds::AtLeast(1));
    t.Number("maxtime", &O::maxtime, "wall-time limit, s", OptionBounds::Above(0));
    t.Number(
        "local_ftol_rel", &O::local_ftol_rel, "ftol_rel of the subsidiary algorithm" + disables);
    t.Number(
        "local_xtol_rel", &O::local_xtol_rel, "xtol_rel of the subsidiary algorithm" + disables);
    t.Integer("local_maxeval",
              &O::local_maxeval,
              "maxeval of the subsidiary algorithm",
              OptionBounds::AtLeast(1));
    t.Number("constraint_tol",
             &O::constraint_tol,
             "NLopt's per-constraint tolerance",
             OptionBounds::AtLeast(0));
    t.Number("feasibility_tol",
             &O::feasibility_tol,
             "a converged point violating constraints by more is reported infeasible",
             OptionBounds::Above(0));
    t.Number("stationarity_tol",
             &O::stationarity_tol,
             "an FTOL/XTOL stop above this relative KKT residual is step_too_small",
             OptionBounds::Above(0));
    t.Number("max_dense_jacobian",
             &O::max_dense_jacobian,
             "refuse when the dense constraint Jacobian has more entries",
             OptionBounds::Above(0));
    t.Integer("slsqp_max_variables",
              &O::slsqp_max_variables,
              "LD_SLSQP: refuse beyond this many variables",
              OptionBounds::AtLeast(1));
    t.Integer("mma_max_inequalities",
              &O::mma_max_inequalities,
              "LD_MMA / LD_CCSAQ: refuse beyond this many inequality rows",
              OptionBounds::AtLeast(0));
    t.Bool("record_history", &O::record_history, "a history row per objective evaluation");
    return t;
  }();
  return table;
}

}  // namespace

bool NloptOptions::IsValid(std::string* error) const { return NloptBinding().Check(*this, error); }

const OptionSchema& NloptOptions::Schema() { return NloptBinding().schema(); }

NloptOptions NloptOptions::Apply(const OptionMap& options, NloptOptions base) {
  return NloptBinding().ApplyValidated(options, std::move(base));
}

std::string NloptResultName(int code) {
  switch (code) {
    case NLOPT_FAILURE:
      return "FAILURE";
    case NLOPT_INVALID_ARGS:
      return "INVALID_ARGS";
    case NLOPT_OUT_OF_MEMORY:
      return "OUT_OF_MEMORY";
    case NLOPT_ROUNDOFF_LIMITED:
      return "ROUNDOFF_LIMITED";
    case NLOPT_FORCED_STOP:
      return "FORCED_STOP";
    case NLOPT_SUCCESS:
      return "SUCCESS";
    case NLOPT_STOPVAL_REACHED:
      return "STOPVAL_REACHED";
    case NLOPT_FTOL_REACHED:
      return "FTOL_REACHED";
    case NLOPT_XTOL_REACHED:
      return "XTOL_REACHED";
    case NLOPT_MAXEVAL_REACHED:
      return "MAXEVAL_REACHED";
    case NLOPT_MAXTIME_REACHED:
      return "MAXTIME_REACHED";
  }
  return "UNKNOWN_RESULT(" + std::to_string(code) + ")";
}

SolveStatus MapNloptResult(int code, bool evaluation_failed) {
  switch (code) {
    case NLOPT_SUCCESS:
    case NLOPT_STOPVAL_REACHED:
    case NLOPT_FTOL_REACHED:
    case NLOPT_XTOL_REACHED:
      return SolveStatus::kConverged;
    case NLOPT_MAXEVAL_REACHED:
    case NLOPT_MAXTIME_REACHED:
      return SolveStatus::kMaxTime;
    case NLOPT_ROUNDOFF_LIMITED:
      return SolveStatus::kRoundoffLimited;
    case NLOPT_INVALID_ARGS:
      return SolveStatus::kInvalidInput;
    case NLOPT_FORCED_STOP:
      return evaluation_failed ? SolveStatus::kNumericalFailure : SolveStatus::kError;
    default:
      return SolveStatus::kError;
  }
}

NlpSolution SolveNlpWithNlopt(const Nlp& nlp, const Vec& z0, const NloptOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("nlopt options: " + error);
  const int n = nlp.num_variables();
  if (z0.size() != n) {
    throw std::invalid_argument("SolveNlpWithNlopt: starting point has size " +
                                std::to_string(z0.size()) + ", the NLP has " + std::to_string(n) +
                                " variables");
  }
  NlpSolution out;
  out.z = z0;
  NloptProblem problem(nlp, options);
  out.stats["nlopt_equalities"] = problem.num_eq();
  out.stats["nlopt_inequalities"] = problem.num_ineq();

  const std::string refusal = Refusal(options, n, problem.num_eq(), problem.num_ineq());
  if (!refusal.empty()) {
    out.status = SolveStatus::kNotApplicable;
    out.solver_status = "not_run";
    out.message = "nlopt " + options.algorithm + " refused: " + refusal;
    return out;
  }

  // Start inside the bounds (NLopt requires it).
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) {
    x[i] = std::clamp(
        z0[i], problem.z_lower()[i], std::max(problem.z_lower()[i], problem.z_upper()[i]));
  }
  auto bound = [](double v) { return v >= kNoBound ? HUGE_VAL : v <= -kNoBound ? -HUGE_VAL : v; };
  std::vector<double> lower(n), upper(n);
  for (int i = 0; i < n; ++i) {
    lower[i] = bound(problem.z_lower()[i]);
    upper[i] = bound(problem.z_upper()[i]);
  }

  int code = NLOPT_FAILURE;
  double f = NAN;
  std::string message;
  try {
    nlopt::opt opt(FindAlgorithm(options.algorithm)->algorithm, n);
    opt.set_lower_bounds(lower);
    opt.set_upper_bounds(upper);
    opt.set_min_objective(&NloptProblem::Objective, &problem);
    if (problem.num_eq() > 0) {
      opt.add_equality_mconstraint(&NloptProblem::Equalities,
                                   &problem,
                                   std::vector<double>(problem.num_eq(), options.constraint_tol));
    }
    if (problem.num_ineq() > 0) {
      opt.add_inequality_mconstraint(
          &NloptProblem::Inequalities,
          &problem,
          std::vector<double>(problem.num_ineq(), options.constraint_tol));
    }
    opt.set_ftol_rel(options.ftol_rel);
    opt.set_xtol_rel(options.xtol_rel);
    opt.set_maxeval(options.maxeval);
    opt.set_maxtime(options.maxtime);
    if (IsAuglag(options.algorithm)) {
      nlopt::opt local(FindAlgorithm(options.local_algorithm)->algorithm, n);
      local.set_ftol_rel(options.local_ftol_rel);
      local.set_xtol_rel(options.local_xtol_rel);
      local.set_maxeval(options.local_maxeval);
      opt.set_local_optimizer(local);
    }
    code = opt.optimize(x, f);
  } catch (const nlopt::roundoff_limited&) {
    code = NLOPT_ROUNDOFF_LIMITED;
  } catch (const nlopt::forced_stop&) {
    code = NLOPT_FORCED_STOP;
  } catch (const std::invalid_argument& e) {
    code = NLOPT_INVALID_ARGS;
    message += std::string("NLopt: invalid argument: ") + e.what() + ". ";
  } catch (const std::bad_alloc&) {
    code = NLOPT_OUT_OF_MEMORY;
    message += "NLopt: out of memory. ";
  } catch (const std::runtime_error& e) {
    code = NLOPT_FAILURE;
    message += std::string("NLopt: ") + e.what() + ". ";
  }

  out.solver_status = NloptResultName(code);
  out.status = MapNloptResult(code, problem.evaluation_failed());
  out.iterations = problem.evaluations();
  out.history = std::move(problem.history());
  if (problem.evaluation_failed()) message += problem.failure() + ". ";

  // The returned point: NLopt's x, unless it is not finite (then the last point whose
  // objective evaluated).
  Vec z = Eigen::Map<const Vec>(x.data(), n);
  if (!z.allFinite()) z = problem.last_good_z().size() == n ? problem.last_good_z() : z0;
  out.z = z;
  out.has_iterate = problem.evaluations() > 0;
  double fz = NAN;
  if (out.has_iterate && nlp.Objective(z, &fz)) out.objective = fz;

  // NLopt's convergence tests do not look at feasibility: check it.
  const double violation = NlpViolation(nlp, z);
  out.stats["nlopt_final_violation"] = violation;
  if (out.status == SolveStatus::kConverged && !(violation <= options.feasibility_tol)) {
    out.status = SolveStatus::kInfeasible;
    message += "NLopt reported " + out.solver_status + " at a point violating the constraints by " +
               std::to_string(violation) + " > feasibility_tol " +
               std::to_string(options.feasibility_tol) + ". ";
  }
  // Constraints within 1e-4 (relative) count as active: looser than feasibility_tol, so that
  // rows approached from the feasible side (MMA, CCSAQ, AUGLAG's slack) are balanced too.
  const bool size_test = code == NLOPT_FTOL_REACHED || code == NLOPT_XTOL_REACHED;
  const double stationarity = out.status == SolveStatus::kConverged && size_test
                                  ? NlpStationarity(nlp, z, std::max(1e-4, options.feasibility_tol))
                                  : NAN;
  if (size_test) out.stats["nlopt_stationarity"] = stationarity;
  if (out.status == SolveStatus::kConverged && size_test &&
      !(stationarity <= options.stationarity_tol)) {
    out.status = SolveStatus::kStepTooSmall;
    message += "NLopt reported " + out.solver_status +
               " at a point that is not stationary: relative KKT residual " +
               std::to_string(stationarity) + " > stationarity_tol " +
               std::to_string(options.stationarity_tol) + ". ";
  }
  if (code == NLOPT_ROUNDOFF_LIMITED) {
    message += "roundoff limited: the last point is kept (usually still useful). ";
  }
  out.message = message + "NLopt " + options.algorithm +
                (IsAuglag(options.algorithm) ? "(" + options.local_algorithm + ")" : "") + ": " +
                out.solver_status + " after " + std::to_string(out.iterations) + " evaluations";
  return out;
}

}  // namespace ocpb
