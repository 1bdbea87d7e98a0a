#include "solvers/ipopt_adapter.h"

#include <IpIpoptApplication.hpp>
#include <IpJournalist.hpp>
#include <IpRegOptions.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "core/timer.h"

namespace ocpb {
namespace {

using Ipopt::Index;
using Ipopt::Number;

constexpr double kIpoptInfinity = 1e19;  // Ipopt's nlp_{lower,upper}_bound_inf default

// ---- the option table ---------------------------------------------------------------
// Hand-written from Ipopt 3.11's documented options; the unit test compares it with the
// registry of the linked library (IpoptOptionTableMatchesIpopt).
std::vector<IpoptOptionSpec> BuildTable() {
  const auto N = IpoptOptionType::kNumber;
  const auto I = IpoptOptionType::kInteger;
  const auto S = IpoptOptionType::kString;
  const std::vector<std::string> yes_no = {"no", "yes"};
  return {
      // termination
      {"tol", N, {}},
      {"max_iter", I, {}},
      {"max_cpu_time", N, {}},
      {"dual_inf_tol", N, {}},
      {"constr_viol_tol", N, {}},
      {"compl_inf_tol", N, {}},
      {"acceptable_tol", N, {}},
      {"acceptable_iter", I, {}},
      {"acceptable_dual_inf_tol", N, {}},
      {"acceptable_constr_viol_tol", N, {}},
      {"acceptable_compl_inf_tol", N, {}},
      {"acceptable_obj_change_tol", N, {}},
      {"diverging_iterates_tol", N, {}},
      {"mu_target", N, {}},
      // barrier parameter
      {"mu_strategy", S, {"monotone", "adaptive"}},
      {"mu_oracle", S, {"probing", "loqo", "quality-function"}},
      {"mu_init", N, {}},
      {"mu_min", N, {}},
      {"mu_max", N, {}},
      {"mu_linear_decrease_factor", N, {}},
      {"mu_superlinear_decrease_power", N, {}},
      {"barrier_tol_factor", N, {}},
      {"adaptive_mu_globalization", S, {"kkt-error", "obj-constr-filter", "never-monotone-mode"}},
      // Hessian
      {"hessian_approximation", S, {"exact", "limited-memory"}},
      {"limited_memory_max_history", I, {}},
      {"limited_memory_update_type", S, {"bfgs", "sr1"}},
      {"limited_memory_initialization",
       S,
       {"scalar1", "scalar2", "scalar3", "scalar4", "constant"}},
      {"limited_memory_init_val", N, {}},
      {"limited_memory_max_skipping", I, {}},
      // initialization
      {"bound_push", N, {}},
      {"bound_frac", N, {}},
      {"slack_bound_push", N, {}},
      {"slack_bound_frac", N, {}},
      {"bound_mult_init_val", N, {}},
      {"bound_mult_init_method", S, {"constant", "mu-based"}},
      {"constr_mult_init_max", N, {}},
      {"least_square_init_primal", S, yes_no},
      {"least_square_init_duals", S, yes_no},
      // warm start (applied only when SolveNlpWithIpopt is given multipliers; the bound push,
      // the multipliers' push and mu_init are IpoptOptions fields)
      {"warm_start_bound_frac", N, {}},
      {"warm_start_slack_bound_push", N, {}},
      {"warm_start_slack_bound_frac", N, {}},
      {"warm_start_mult_init_max", N, {}},
      // line search
      {"line_search_method", S, {"filter", "cg-penalty", "penalty"}},
      {"max_soc", I, {}},
      {"accept_every_trial_step", S, yes_no},
      {"accept_after_max_steps", I, {}},
      {"alpha_for_y",
       S,
       {"primal",
        "bound-mult",
        "min",
        "max",
        "full",
        "min-dual-infeas",
        "safer-min-dual-infeas",
        "primal-and-full",
        "dual-and-full",
        "acceptor"}},
      {"watchdog_shortened_iter_trigger", I, {}},
      {"watchdog_trial_iter_max", I, {}},
      {"tiny_step_tol", N, {}},
      {"corrector_type", S, {"none", "affine", "primal-dual"}},
      {"recalc_y", S, yes_no},
      // linear solver: only MUMPS is built in (no HSL, no Pardiso)
      {"linear_solver", S, {"mumps"}},
      {"linear_system_scaling", S, {"none", "slack-based"}},
      {"mumps_pivtol", N, {}},
      {"mumps_pivtolmax", N, {}},
      {"mumps_mem_percent", I, {}},
      {"mumps_permuting_scaling", I, {}},
      {"mumps_pivot_order", I, {}},
      {"mumps_scaling", I, {}},
      // scaling (user-scaling needs scaling data the Nlp does not carry; equilibration needs MC19)
      {"nlp_scaling_method", S, {"none", "gradient-based"}},
      {"obj_scaling_factor", N, {}},
      {"nlp_scaling_max_gradient", N, {}},
      {"nlp_scaling_min_value", N, {}},
      {"nlp_scaling_obj_target_gradient", N, {}},
      {"nlp_scaling_constr_target_gradient", N, {}},
      // NLP
      {"bound_relax_factor", N, {}},
      {"honor_original_bounds", S, yes_no},
      {"fixed_variable_treatment", S, {"make_parameter", "make_constraint", "relax_bounds"}},
      {"check_derivatives_for_naninf", S, yes_no},
      {"jac_c_constant", S, yes_no},
      {"jac_d_constant", S, yes_no},
      {"hessian_constant", S, yes_no},
      {"kappa_d", N, {}},
      // derivative checker
      {"derivative_test", S, {"none", "first-order", "second-order", "only-second-order"}},
      {"derivative_test_tol", N, {}},
      {"derivative_test_perturbation", N, {}},
      {"derivative_test_print_all", S, yes_no},
      {"derivative_test_first_index", I, {}},
      {"point_perturbation_radius", N, {}},
      // output
      {"print_level", I, {}},
      {"print_frequency_iter", I, {}},
      {"print_user_options", S, yes_no},
      {"print_timing_statistics", S, yes_no},
      {"output_file", S, {}},
      {"file_print_level", I, {}},
      // restoration phase
      {"expect_infeasible_problem", S, yes_no},
      {"expect_infeasible_problem_ctol", N, {}},
      {"required_infeasibility_reduction", N, {}},
      {"max_resto_iter", I, {}},
      {"start_with_resto", S, yes_no},
      {"resto_penalty_parameter", N, {}},
      // step computation
      {"max_refinement_steps", I, {}},
      {"min_refinement_steps", I, {}},
      {"first_hessian_perturbation", N, {}},
      {"max_hessian_perturbation", N, {}},
      {"min_hessian_perturbation", N, {}},
      {"jacobian_regularization_value", N, {}},
      {"mehrotra_algorithm", S, yes_no},
      {"neg_curv_test_tol", N, {}},
  };
}

// ---- the TNLP -------------------------------------------------------------------------

// Ipopt's view of an ocpb::Nlp. Structure (sizes, triplets) is read once from the Nlp; values are
// computed on demand. No exception leaves a callback: an evaluation that fails or throws returns
// false, which Ipopt treats as an invalid number (it then cuts the step back or stops with
// Invalid_Number_Detected).
class NlpTnlp final : public Ipopt::TNLP {
 public:
  NlpTnlp(const Nlp& nlp, const Vec& z0, const NlpMultipliers& y0, bool exact_hessian)
      : nlp_(nlp),
        z0_(z0),
        y0_(y0),
        exact_hessian_(exact_hessian),
        n_(nlp.num_variables()),
        m_(nlp.num_constraints()),
        watch_() {}

  bool get_nlp_info(Index& n,
                    Index& m,
                    Index& nnz_jac_g,
                    Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = n_;
    m = m_;
    nnz_jac_g = static_cast<Index>(nlp_.jacobian_rows().size());
    nnz_h_lag = exact_hessian_ ? static_cast<Index>(nlp_.hessian_rows().size()) : 0;
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(
      Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    Vec zl, zu, gl, gu;
    try {
      nlp_.Bounds(&zl, &zu, &gl, &gu);
    } catch (const std::exception& e) {
      Note(std::string("Nlp::Bounds threw: ") + e.what());
      return false;
    }
    if (zl.size() != n || zu.size() != n || gl.size() != m || gu.size() != m) {
      Note("Nlp::Bounds returned vectors of the wrong size");
      return false;
    }
    for (Index i = 0; i < n; ++i) {
      x_l[i] = Clip(zl[i]);
      x_u[i] = Clip(zu[i]);
    }
    for (Index j = 0; j < m; ++j) {
      g_l[j] = Clip(gl[j]);
      g_u[j] = Clip(gu[j]);
    }
    return true;
  }

  // Ipopt asks for multipliers (init_z, init_lambda) only with warm_start_init_point=yes, which
  // SolveNlpWithIpopt sets exactly when it was given them.
  bool get_starting_point(Index n,
                          bool init_x,
                          Number* x,
                          bool init_z,
                          Number* z_L,
                          Number* z_U,
                          Index m,
                          bool init_lambda,
                          Number* lambda) override {
    if ((init_z || init_lambda) && y0_.empty()) {
      Note("Ipopt asked for starting multipliers, but none were given");
      return false;
    }
    if (init_x) Eigen::Map<Vec>(x, n) = z0_;
    if (init_z) {
      Eigen::Map<Vec>(z_L, n) = y0_.z_lower;
      Eigen::Map<Vec>(z_U, n) = y0_.z_upper;
    }
    if (init_lambda) Eigen::Map<Vec>(lambda, m) = y0_.lambda;
    return true;
  }

  bool eval_f(Index n, const Number* x, bool /*new_x*/, Number& obj_value) override {
    return Guard("Objective", [&] {
      double f = NAN;
      const bool ok = nlp_.Objective(Eigen::Map<const Vec>(x, n), &f);
      obj_value = f;
      return ok && std::isfinite(f);
    });
  }

  bool eval_grad_f(Index n, const Number* x, bool /*new_x*/, Number* grad_f) override {
    return Guard("Gradient", [&] {
      Eigen::Map<Vec> g(grad_f, n);
      return nlp_.Gradient(Eigen::Map<const Vec>(x, n), g) && g.allFinite();
    });
  }

  bool eval_g(Index n, const Number* x, bool /*new_x*/, Index m, Number* g) override {
    return Guard("Constraints", [&] {
      Eigen::Map<Vec> gv(g, m);
      return nlp_.Constraints(Eigen::Map<const Vec>(x, n), gv) && gv.allFinite();
    });
  }

  bool eval_jac_g(Index n,
                  const Number* x,
                  bool /*new_x*/,
                  Index /*m*/,
                  Index nele_jac,
                  Index* iRow,
                  Index* jCol,
                  Number* values) override {
    if (values == nullptr) {
      const auto& rows = nlp_.jacobian_rows();
      const auto& cols = nlp_.jacobian_cols();
      for (Index k = 0; k < nele_jac; ++k) {
        iRow[k] = rows[k];
        jCol[k] = cols[k];
      }
      return true;
    }
    return Guard("JacobianValues", [&] {
      Eigen::Map<Vec> v(values, nele_jac);
      return nlp_.JacobianValues(Eigen::Map<const Vec>(x, n), v) && v.allFinite();
    });
  }

  bool eval_h(Index n,
              const Number* x,
              bool /*new_x*/,
              Number obj_factor,
              Index m,
              const Number* lambda,
              bool /*new_lambda*/,
              Index nele_hess,
              Index* iRow,
              Index* jCol,
              Number* values) override {
    if (!exact_hessian_) return false;
    if (values == nullptr) {
      // Ipopt wants the lower triangle; core/nlp.h guarantees row >= col.
      const auto& rows = nlp_.hessian_rows();
      const auto& cols = nlp_.hessian_cols();
      for (Index k = 0; k < nele_hess; ++k) {
        iRow[k] = rows[k];
        jCol[k] = cols[k];
      }
      return true;
    }
    return Guard("HessianValues", [&] {
      Eigen::Map<Vec> v(values, nele_hess);
      return nlp_.HessianValues(
                 Eigen::Map<const Vec>(x, n), obj_factor, Eigen::Map<const Vec>(lambda, m), v) &&
             v.allFinite();
    });
  }

  void finalize_solution(Ipopt::SolverReturn /*status*/,
                         Index n,
                         const Number* x,
                         const Number* z_L,
                         const Number* z_U,
                         Index m,
                         const Number* /*g*/,
                         const Number* lambda,
                         Number obj_value,
                         const Ipopt::IpoptData* /*ip_data*/,
                         Ipopt::IpoptCalculatedQuantities* /*ip_cq*/) override {
    finalized_ = true;
    z_ = Eigen::Map<const Vec>(x, n);
    lambda_ = m > 0 && lambda != nullptr ? Vec(Eigen::Map<const Vec>(lambda, m)) : Vec(m);
    if (m > 0 && lambda == nullptr) lambda_.setConstant(NAN);
    z_lower_ = z_L != nullptr ? Vec(Eigen::Map<const Vec>(z_L, n)) : Vec::Constant(n, NAN);
    z_upper_ = z_U != nullptr ? Vec(Eigen::Map<const Vec>(z_U, n)) : Vec::Constant(n, NAN);
    objective_ = obj_value;
  }

  bool intermediate_callback(Ipopt::AlgorithmMode mode,
                             Index iter,
                             Number obj_value,
                             Number inf_pr,
                             Number inf_du,
                             Number /*mu*/,
                             Number /*d_norm*/,
                             Number /*regularization_size*/,
                             Number /*alpha_du*/,
                             Number /*alpha_pr*/,
                             Index /*ls_trials*/,
                             const Ipopt::IpoptData* /*ip_data*/,
                             Ipopt::IpoptCalculatedQuantities* /*ip_cq*/) override {
    IterationRecord r;
    r.iteration = iter;
    r.J = obj_value;
    r.primal_inf = inf_pr;
    r.dual_inf = inf_du;
    r.cpu_seconds = watch_.cpu();
    history_.push_back(r);
    if (mode == Ipopt::RestorationPhaseMode) ++restoration_iterations_;
    return true;
  }

  bool finalized() const { return finalized_; }
  const Vec& z() const { return z_; }
  const Vec& lambda() const { return lambda_; }
  const Vec& z_lower() const { return z_lower_; }
  const Vec& z_upper() const { return z_upper_; }
  double objective() const { return objective_; }
  std::vector<IterationRecord>& history() { return history_; }
  const std::string& notes() const { return notes_; }
  int restoration_iterations() const { return restoration_iterations_; }

 private:
  static double Clip(double v) {
    if (v >= kIpoptInfinity) return 2.0 * kIpoptInfinity;
    if (v <= -kIpoptInfinity) return -2.0 * kIpoptInfinity;
    return v;
  }

  template <class Fn>
  bool Guard(const char* what, Fn&& fn) {
    try {
      if (fn()) return true;
      ++failed_evaluations_;
      if (failed_evaluations_ == 1) Note(std::string("Nlp::") + what + " failed (NaN/inf)");
      return false;
    } catch (const std::exception& e) {
      Note(std::string("Nlp::") + what + " threw: " + e.what());
    } catch (...) {
      Note(std::string("Nlp::") + what + " threw a non-standard exception");
    }
    return false;
  }

  void Note(const std::string& s) {
    if (notes_.size() < 2000) notes_ += (notes_.empty() ? "" : "; ") + s;
  }

  const Nlp& nlp_;
  const Vec z0_;
  const NlpMultipliers y0_;
  const bool exact_hessian_;
  const Index n_, m_;
  Stopwatch watch_;
  bool finalized_ = false;
  Vec z_, lambda_, z_lower_, z_upper_;
  double objective_ = NAN;
  std::vector<IterationRecord> history_;
  std::string notes_;
  int failed_evaluations_ = 0;
  int restoration_iterations_ = 0;
};

bool Apply(Ipopt::OptionsList& list, const IpoptOptionValue& v) {
  switch (v.type) {
    case IpoptOptionType::kNumber:
      return list.SetNumericValue(v.name, v.number);
    case IpoptOptionType::kInteger:
      return list.SetIntegerValue(v.name, v.integer);
    case IpoptOptionType::kString:
      return list.SetStringValue(v.name, v.text);
  }
  return false;
}

IpoptOptionValue NumberOption(const std::string& name, double v) {
  IpoptOptionValue o;
  o.name = name;
  o.type = IpoptOptionType::kNumber;
  o.number = v;
  return o;
}
IpoptOptionValue IntegerOption(const std::string& name, int v) {
  IpoptOptionValue o;
  o.name = name;
  o.type = IpoptOptionType::kInteger;
  o.integer = v;
  return o;
}
IpoptOptionValue TextOption(const std::string& name, const std::string& v) {
  IpoptOptionValue o;
  o.name = name;
  o.type = IpoptOptionType::kString;
  o.text = v;
  return o;
}

// Every option a solve gives Ipopt, in order (a later setting of a name wins): OCPBench's
// fields, the warm start's, the pass-through options, the Hessian forced last. One list for the
// solve and for the check that asks Ipopt about the options (IpoptAcceptsTogether).
std::vector<IpoptOptionValue> IpoptSettings(const IpoptOptions& options, bool exact, bool warm) {
  std::vector<IpoptOptionValue> settings = {
      TextOption("sb", "yes"),  // no banner
      NumberOption("tol", options.tol),
      IntegerOption("max_iter", options.max_iter),
      NumberOption("acceptable_tol", options.acceptable_tol),
      IntegerOption("acceptable_iter", options.acceptable_iter),
      NumberOption("max_cpu_time", options.max_cpu_time),
      TextOption("mu_strategy", options.mu_strategy),
      TextOption("linear_solver", options.linear_solver),
      IntegerOption("mumps_pivot_order",
                    options.mumps_pivot_order >= 0 ? options.mumps_pivot_order : (exact ? 0 : 7)),
      TextOption("nlp_scaling_method", options.nlp_scaling_method),
      NumberOption("obj_scaling_factor", options.obj_scaling_factor),
      NumberOption("nlp_scaling_max_gradient", options.nlp_scaling_max_gradient),
      IntegerOption("print_level", options.print_level),
  };
  if (warm) {
    // Ipopt reads the given multipliers (TNLP::get_starting_point with init_z, init_lambda)
    // and moves the point only by these pushes into the bounds' interior.
    const double push = options.warm_start_bound_push;
    settings.push_back(TextOption("warm_start_init_point", "yes"));
    settings.push_back(NumberOption("warm_start_bound_push", push));
    settings.push_back(NumberOption("warm_start_bound_frac", std::min(push, 0.5)));
    settings.push_back(NumberOption("warm_start_slack_bound_push", push));
    settings.push_back(NumberOption("warm_start_slack_bound_frac", std::min(push, 0.5)));
    settings.push_back(
        NumberOption("warm_start_mult_bound_push", options.warm_start_mult_bound_push));
  }
  settings.insert(settings.end(), options.extra.begin(), options.extra.end());
  // A warm start's barrier parameter wins over a pass-through mu_init (meant for cold starts).
  if (warm) settings.push_back(NumberOption("mu_init", options.warm_start_mu_init));
  // Forced last: an extra "hessian_approximation=exact" cannot ask for a Hessian that is absent.
  settings.push_back(TextOption("hessian_approximation", exact ? "exact" : "limited-memory"));
  return settings;
}

// The smallest NLP that builds every part of Ipopt's algorithm a solve of OCPBench's builds: two
// variables (one bounded on both sides, one free), an equality and an inequality row, an exact
// Hessian, multipliers for a warm start. Its solve stops after three iterations: what matters
// is that Ipopt builds and initializes its algorithm with the options and takes its first
// steps, which is where it checks the rules that tie options together.
class ProbeTnlp final : public Ipopt::TNLP {
 public:
  bool get_nlp_info(
      Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = 2;
    m = 2;
    nnz_jac_g = 4;
    nnz_h_lag = 2;
    style = C_STYLE;
    return true;
  }
  bool get_bounds_info(Index, Number* x_l, Number* x_u, Index, Number* g_l, Number* g_u) override {
    x_l[0] = -1.0;
    x_u[0] = 2.0;
    x_l[1] = -kIpoptInfinity;
    x_u[1] = kIpoptInfinity;
    g_l[0] = g_u[0] = 1.0;
    g_l[1] = -kIpoptInfinity;
    g_u[1] = 3.0;
    return true;
  }
  bool get_starting_point(Index,
                          bool init_x,
                          Number* x,
                          bool init_z,
                          Number* z_l,
                          Number* z_u,
                          Index,
                          bool init_lambda,
                          Number* lambda) override {
    if (init_x) x[0] = x[1] = 0.5;
    if (init_z) z_l[0] = z_l[1] = z_u[0] = z_u[1] = 1.0;
    if (init_lambda) lambda[0] = lambda[1] = 0.0;
    return true;
  }
  bool eval_f(Index, const Number* x, bool, Number& f) override {
    f = x[0] * x[0] + x[1] * x[1];
    return true;
  }
  bool eval_grad_f(Index, const Number* x, bool, Number* g) override {
    g[0] = 2.0 * x[0];
    g[1] = 2.0 * x[1];
    return true;
  }
  bool eval_g(Index, const Number* x, bool, Index, Number* g) override {
    g[0] = x[0] + x[1];
    g[1] = x[0] * x[0] + x[1];
    return true;
  }
  bool eval_jac_g(Index,
                  const Number* x,
                  bool,
                  Index,
                  Index,
                  Index* rows,
                  Index* cols,
                  Number* values) override {
    if (values == nullptr) {
      const Index r[] = {0, 0, 1, 1}, c[] = {0, 1, 0, 1};
      std::copy(r, r + 4, rows);
      std::copy(c, c + 4, cols);
    } else {
      values[0] = values[1] = values[3] = 1.0;
      values[2] = 2.0 * x[0];
    }
    return true;
  }
  bool eval_h(Index,
              const Number*,
              bool,
              Number obj_factor,
              Index,
              const Number* lambda,
              bool,
              Index,
              Index* rows,
              Index* cols,
              Number* values) override {
    if (values == nullptr) {
      rows[0] = cols[0] = 0;
      rows[1] = cols[1] = 1;
    } else {
      values[0] = 2.0 * obj_factor + 2.0 * lambda[1];
      values[1] = 2.0 * obj_factor;
    }
    return true;
  }
  void finalize_solution(Ipopt::SolverReturn,
                         Index,
                         const Number*,
                         const Number*,
                         const Number*,
                         Index,
                         const Number*,
                         const Number*,
                         Number,
                         const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {}
};

// Keeps what Ipopt says at its error level (the text of an option it refuses), whatever the
// options' print_level.
class MessageJournal final : public Ipopt::Journal {
 public:
  MessageJournal() : Ipopt::Journal("ocpb-messages", Ipopt::J_ERROR) {}
  const std::string& text() const { return text_; }
  void Clear() { text_.clear(); }

 protected:
  void PrintImpl(Ipopt::EJournalCategory, Ipopt::EJournalLevel, const char* str) override {
    if (text_.size() < 4000) text_ += str;
  }
  void PrintfImpl(Ipopt::EJournalCategory,
                  Ipopt::EJournalLevel,
                  const char* format,
                  va_list ap) override {
    char buffer[2048];
    std::vsnprintf(buffer, sizeof buffer, format, ap);
    PrintImpl(Ipopt::J_MAIN, Ipopt::J_ERROR, buffer);
  }
  void FlushBufferImpl() override {}

 private:
  std::string text_;
};

// Ipopt's reason, as one line: the message of the exception it reported ("Option
// \"mumps_pivtolmax\": This value must be between mumps_pivtol and 1."), without the
// assertion's text before it, or its first line.
std::string IpoptReason(const std::string& text) {
  std::string reason = text;
  const size_t message = reason.find("Exception message: ");
  if (message != std::string::npos) reason = reason.substr(message + 19);
  const size_t assertion = reason.find(" evaluated false: ");
  if (assertion != std::string::npos) reason = reason.substr(assertion + 18);
  reason = reason.substr(0, reason.find('\n'));
  while (!reason.empty() && (reason.back() == ' ' || reason.back() == '.')) reason.pop_back();
  return reason.empty() ? "Ipopt refuses the options (Invalid_Option)" : reason;
}

// One start of Ipopt with `settings` on ProbeTnlp: "" when Ipopt builds its algorithm with
// them, else its reason. The solver's output file is left out (Ipopt would create it; its
// place is checked as every output's is), and so is its console log. One application serves
// every start (its options cleared first): registering Ipopt's options is most of a start's
// cost. The caller holds the lock that guards it.
std::string AskIpopt(std::vector<IpoptOptionValue> settings) {
  static const Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  static const Ipopt::SmartPtr<MessageJournal> journal = [] {
    Ipopt::SmartPtr<MessageJournal> j = new MessageJournal();
    app->Jnlst()->AddJournal(Ipopt::GetRawPtr(j));
    return j;
  }();
  journal->Clear();
  app->Options()->clear();
  settings.erase(std::remove_if(settings.begin(),
                                settings.end(),
                                [](const IpoptOptionValue& v) { return v.name == "output_file"; }),
                 settings.end());
  settings.push_back(IntegerOption("print_level", 0));
  // Three iterations: Ipopt checks some rules only when it first takes a step (alpha_for_y's
  // "acceptor" outside the penalty line searches, at the first accepted trial point).
  settings.push_back(IntegerOption("max_iter", 3));
  // Ipopt's derivative checker ties no option to another (and 3.11's leaks memory).
  settings.push_back(TextOption("derivative_test", "none"));
  for (const IpoptOptionValue& v : settings) {
    if (!Apply(*app->Options(), v))
      return "option '" + v.name + "': " + IpoptReason(journal->text());
  }
  Ipopt::ApplicationReturnStatus status = app->Initialize("");
  if (status == Ipopt::Solve_Succeeded) {
    Ipopt::SmartPtr<Ipopt::TNLP> probe = new ProbeTnlp();
    try {
      status = app->OptimizeTNLP(probe);
    } catch (const std::exception& e) {
      return std::string("an exception from Ipopt: ") + e.what();
    }
  }
  if (status != Ipopt::Invalid_Option) return "";
  return IpoptReason(journal->text());
}
}  // namespace

// ---- options ---------------------------------------------------------------------------

// The table with each number and integer option's range from the linked Ipopt's registry.
std::vector<IpoptOptionSpec> TableWithIpoptsRanges() {
  std::vector<IpoptOptionSpec> table = BuildTable();
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  Ipopt::SmartPtr<Ipopt::RegisteredOptions> reg = app->RegOptions();
  for (IpoptOptionSpec& s : table) {
    if (s.type == IpoptOptionType::kString) continue;
    Ipopt::SmartPtr<const Ipopt::RegisteredOption> opt = reg->GetOption(s.name);
    if (!Ipopt::IsValid(opt)) continue;  // reported by IpoptOptionTableMatchesIpopt
    s.default_value = s.type == IpoptOptionType::kNumber
                          ? opt->DefaultNumber()
                          : static_cast<double>(opt->DefaultInteger());
    if (s.type == IpoptOptionType::kNumber) {
      if (opt->HasLower()) {
        s.bounds.min = opt->LowerNumber();
        s.bounds.min_exclusive = opt->LowerStrict();
      }
      if (opt->HasUpper()) {
        s.bounds.max = opt->UpperNumber();
        s.bounds.max_exclusive = opt->UpperStrict();
      }
    } else {
      if (opt->HasLower()) s.bounds.min = opt->LowerInteger();
      if (opt->HasUpper()) s.bounds.max = opt->UpperInteger();
    }
  }
  return table;
}

bool IpoptRegistryAccepts(const IpoptOptionValue& v, std::string* error) {
  // One registry, made once: Ipopt's own answer for a value, as SetXValue would give it when
  // the solve starts.
  static const Ipopt::SmartPtr<Ipopt::RegisteredOptions> reg = [] {
    Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
    return app->RegOptions();
  }();
  Ipopt::SmartPtr<const Ipopt::RegisteredOption> opt = reg->GetOption(v.name);
  bool ok = Ipopt::IsValid(opt);
  if (ok) {
    switch (v.type) {
      case IpoptOptionType::kNumber:
        ok = opt->Type() == Ipopt::OT_Number && opt->IsValidNumberSetting(v.number);
        break;
      case IpoptOptionType::kInteger:
        ok = opt->Type() == Ipopt::OT_Integer && opt->IsValidIntegerSetting(v.integer);
        break;
      case IpoptOptionType::kString:
        ok = opt->Type() == Ipopt::OT_String && opt->IsValidStringSetting(v.text);
        break;
    }
  }
  if (!ok && error) {
    *error = "ipopt option '" + v.name + "': the linked Ipopt refuses the value" +
             (v.type == IpoptOptionType::kString ? " '" + v.text + "'" : std::string());
  }
  return ok;
}

bool IpoptAcceptsTogether(const IpoptOptions& options, std::string* error) {
  // OCPBench's own fields alone: each is within Ipopt's registered range, and no rule of Ipopt
  // ties two of them (the option tests try their combinations against Ipopt); asking Ipopt
  // would cost every solve a few starts (tens of ms under the sanitizers) for nothing.
  if (options.extra.empty()) return true;
  // The starts a solve may make: an exact or a limited-memory Hessian (auto and exact become
  // limited-memory on an NLP without one), cold or warm (mesh refinement's later meshes).
  struct Start {
    bool exact, warm;
    const char* with;
  };
  std::vector<Start> starts;
  for (const bool warm : {false, true}) {
    if (options.hessian_approximation != "limited-memory") {
      starts.push_back({true, warm, warm ? " (in a warm-started solve)" : ""});
    }
    starts.push_back({false,
                      warm,
                      warm ? " (in a warm-started solve with a limited-memory Hessian)"
                           : " (in a solve with a limited-memory Hessian)"});
  }
  starts.front().with = "";
  // Ipopt's answer for one list of settings is always the same: asked once a process.
  static std::mutex mutex;
  static std::map<std::string, std::string> answers;
  for (const Start& start : starts) {
    const std::vector<IpoptOptionValue> settings = IpoptSettings(options, start.exact, start.warm);
    std::string key;
    for (const IpoptOptionValue& v : settings) {
      char number[64];
      std::snprintf(number, sizeof number, "%.17g/%d", v.number, v.integer);
      key += v.name + '=' + number + '/' + v.text + '\n';
    }
    std::string answer;
    {
      const std::lock_guard<std::mutex> hold(mutex);
      auto found = answers.find(key);
      if (found == answers.end()) found = answers.emplace(key, AskIpopt(settings)).first;
      answer = found->second;
    }
    if (answer.empty()) continue;
    if (error) {
      *error = "the linked Ipopt refuses these options together" + std::string(start.with) + ": " +
               answer + " (Ipopt's rule, checked before any work)";
    }
    return false;
  }
  return true;
}

const std::vector<IpoptOrderedPair>& IpoptOrderedPairs() {
  static const std::vector<IpoptOrderedPair> pairs = {
      {"mumps_pivtol", "mumps_pivtolmax"},
      {"min_refinement_steps", "max_refinement_steps"},
  };
  return pairs;
}

const std::vector<IpoptOptionSpec>& IpoptOptionTable() {
  static const std::vector<IpoptOptionSpec> table = TableWithIpoptsRanges();
  return table;
}

const IpoptOptionSpec* FindIpoptOption(const std::string& name) {
  for (const IpoptOptionSpec& s : IpoptOptionTable()) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

bool IpoptOptionTableMatchesIpopt(std::string* error) {
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  Ipopt::SmartPtr<Ipopt::RegisteredOptions> reg = app->RegOptions();
  std::string problems;
  for (const IpoptOptionSpec& s : IpoptOptionTable()) {
    Ipopt::SmartPtr<const Ipopt::RegisteredOption> opt = reg->GetOption(s.name);
    if (!Ipopt::IsValid(opt)) {
      problems += s.name + ": not registered by Ipopt; ";
      continue;
    }
    const Ipopt::RegisteredOptionType expected =
        s.type == IpoptOptionType::kNumber    ? Ipopt::OT_Number
        : s.type == IpoptOptionType::kInteger ? Ipopt::OT_Integer
                                              : Ipopt::OT_String;
    if (opt->Type() != expected) {
      problems += s.name + ": Ipopt registers another type; ";
      continue;
    }
    for (const std::string& v : s.values) {
      if (!opt->IsValidStringSetting(v)) problems += s.name + ": Ipopt rejects '" + v + "'; ";
    }
  }
  if (error) *error = problems;
  return problems.empty();
}

// ---- status ------------------------------------------------------------------------------

std::string IpoptStatusName(int code) {
  switch (static_cast<Ipopt::ApplicationReturnStatus>(code)) {
    case Ipopt::Solve_Succeeded:
      return "Solve_Succeeded";
    case Ipopt::Solved_To_Acceptable_Level:
      return "Solved_To_Acceptable_Level";
    case Ipopt::Infeasible_Problem_Detected:
      return "Infeasible_Problem_Detected";
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return "Search_Direction_Becomes_Too_Small";
    case Ipopt::Diverging_Iterates:
      return "Diverging_Iterates";
    case Ipopt::User_Requested_Stop:
      return "User_Requested_Stop";
    case Ipopt::Feasible_Point_Found:
      return "Feasible_Point_Found";
    case Ipopt::Maximum_Iterations_Exceeded:
      return "Maximum_Iterations_Exceeded";
    case Ipopt::Restoration_Failed:
      return "Restoration_Failed";
    case Ipopt::Error_In_Step_Computation:
      return "Error_In_Step_Computation";
    case Ipopt::Maximum_CpuTime_Exceeded:
      return "Maximum_CpuTime_Exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
      return "Not_Enough_Degrees_Of_Freedom";
    case Ipopt::Invalid_Problem_Definition:
      return "Invalid_Problem_Definition";
    case Ipopt::Invalid_Option:
      return "Invalid_Option";
    case Ipopt::Invalid_Number_Detected:
      return "Invalid_Number_Detected";
    case Ipopt::Unrecoverable_Exception:
      return "Unrecoverable_Exception";
    case Ipopt::NonIpopt_Exception_Thrown:
      return "NonIpopt_Exception_Thrown";
    case Ipopt::Insufficient_Memory:
      return "Insufficient_Memory";
    case Ipopt::Internal_Error:
      return "Internal_Error";
  }
  return "Unknown_Status(" + std::to_string(code) + ")";
}

SolveStatus MapIpoptStatus(int code) {
  switch (static_cast<Ipopt::ApplicationReturnStatus>(code)) {
    case Ipopt::Solve_Succeeded:
    case Ipopt::Feasible_Point_Found:
      return SolveStatus::kConverged;
    case Ipopt::Solved_To_Acceptable_Level:
      return SolveStatus::kAcceptable;
    case Ipopt::Infeasible_Problem_Detected:
      return SolveStatus::kInfeasible;
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return SolveStatus::kStepTooSmall;
    case Ipopt::Maximum_Iterations_Exceeded:
      return SolveStatus::kMaxIterations;
    case Ipopt::Maximum_CpuTime_Exceeded:
      return SolveStatus::kMaxTime;
    case Ipopt::Diverging_Iterates:
    case Ipopt::Restoration_Failed:
    case Ipopt::Error_In_Step_Computation:
    case Ipopt::Invalid_Number_Detected:
      return SolveStatus::kNumericalFailure;
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
    case Ipopt::Invalid_Problem_Definition:
    case Ipopt::Invalid_Option:
      return SolveStatus::kInvalidInput;
    case Ipopt::User_Requested_Stop:
    case Ipopt::Unrecoverable_Exception:
    case Ipopt::NonIpopt_Exception_Thrown:
    case Ipopt::Insufficient_Memory:
    case Ipopt::Internal_Error:
      return SolveStatus::kError;
  }
  return SolveStatus::kError;
}

std::vector<int> AllIpoptStatusCodes() {
  return {Ipopt::Solve_Succeeded,
          Ipopt::Solved_To_Acceptable_Level,
          Ipopt::Infeasible_Problem_Detected,
          Ipopt::Search_Direction_Becomes_Too_Small,
          Ipopt::Diverging_Iterates,
          Ipopt::User_Requested_Stop,
          Ipopt::Feasible_Point_Found,
          Ipopt::Maximum_Iterations_Exceeded,
          Ipopt::Restoration_Failed,
          Ipopt::Error_In_Step_Computation,
          Ipopt::Maximum_CpuTime_Exceeded,
          Ipopt::Not_Enough_Degrees_Of_Freedom,
          Ipopt::Invalid_Problem_Definition,
          Ipopt::Invalid_Option,
          Ipopt::Invalid_Number_Detected,
          Ipopt::Unrecoverable_Exception,
          Ipopt::NonIpopt_Exception_Thrown,
          Ipopt::Insufficient_Memory,
          Ipopt::Internal_Error};
}

// ---- solve ---------------------------------------------------------------------------------

NlpSolution SolveNlpWithIpopt(const Nlp& nlp,
                              const Vec& z0,
                              const IpoptOptions& options,
                              const NlpMultipliers& y0) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("ipopt options: " + error);
  return SolveNlpWithIpoptUnchecked(nlp, z0, options, y0);
}

NlpSolution SolveNlpWithIpoptUnchecked(const Nlp& nlp,
                                       const Vec& z0,
                                       const IpoptOptions& options,
                                       const NlpMultipliers& y0) {
  if (z0.size() != nlp.num_variables()) {
    throw std::invalid_argument("SolveNlpWithIpopt: starting point has size " +
                                std::to_string(z0.size()) + ", the NLP has " +
                                std::to_string(nlp.num_variables()) + " variables");
  }
  const bool warm = !y0.empty();
  if (warm && !y0.Fits(nlp.num_variables(), nlp.num_constraints())) {
    throw std::invalid_argument(
        "SolveNlpWithIpopt: starting multipliers must be finite, with lambda of size " +
        std::to_string(nlp.num_constraints()) + " and z_lower, z_upper of size " +
        std::to_string(nlp.num_variables()));
  }

  NlpSolution out;
  out.z = z0;
  std::string message;

  // Hessian: exact only when the Nlp has one.
  bool exact = nlp.HasHessian();
  if (options.hessian_approximation == "limited-memory") exact = false;
  if (options.hessian_approximation == "exact" && !nlp.HasHessian()) {
    message +=
        "hessian_approximation=exact requested, but the NLP has no Hessian: using "
        "limited-memory. ";
  }
  out.stats["ipopt_exact_hessian"] = exact ? 1.0 : 0.0;

  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  Ipopt::OptionsList& list = *app->Options();
  const std::vector<IpoptOptionValue> settings = IpoptSettings(options, exact, warm);
  for (const IpoptOptionValue& v : settings) {
    if (!Apply(list, v)) {
      out.status = SolveStatus::kInvalidInput;
      out.solver_status = IpoptStatusName(Ipopt::Invalid_Option);
      out.message = message + "Ipopt rejected option '" + v.name + "'";
      return out;
    }
  }

  // Initialize("") reads no ipopt.opt file, so results never depend on the working directory.
  Ipopt::ApplicationReturnStatus status = app->Initialize("");
  Ipopt::SmartPtr<NlpTnlp> tnlp = new NlpTnlp(nlp, z0, y0, exact);
  if (status == Ipopt::Solve_Succeeded) {
    try {
      status = app->OptimizeTNLP(Ipopt::GetRawPtr(tnlp));
    } catch (const std::exception& e) {
      // Ipopt catches its own and our exceptions; this is a last line of defence.
      status = Ipopt::NonIpopt_Exception_Thrown;
      message += std::string("exception from Ipopt: ") + e.what() + ". ";
    }
  } else {
    message += "Ipopt initialization failed. ";
  }

  out.status = MapIpoptStatus(status);
  out.solver_status = IpoptStatusName(status);
  out.history = std::move(tnlp->history());
  if (tnlp->finalized()) {
    out.z = tnlp->z();
    out.lambda = tnlp->lambda();
    out.z_lower = tnlp->z_lower();
    out.z_upper = tnlp->z_upper();
    out.objective = tnlp->objective();
    out.has_iterate = out.z.allFinite();
    if (!out.has_iterate) out.z = z0;
  }
  Ipopt::SmartPtr<Ipopt::SolveStatistics> stats = app->Statistics();
  if (Ipopt::IsValid(stats)) {
    out.iterations = stats->IterationCount();
    out.stats["ipopt_cpu_seconds"] = stats->TotalCpuTime();
    out.stats["ipopt_wall_seconds"] = stats->TotalWallclockTime();
    Number dual_inf, constr_viol, complementarity, kkt;
    stats->Infeasibilities(dual_inf, constr_viol, complementarity, kkt);
    out.stats["ipopt_dual_inf"] = dual_inf;
    out.stats["ipopt_constr_viol"] = constr_viol;
    out.stats["ipopt_complementarity"] = complementarity;
    out.stats["ipopt_kkt_error"] = kkt;
    Index n_f, n_g, n_df, n_dg, n_h;
    stats->NumberOfEvaluations(n_f, n_g, n_df, n_dg, n_h);
    out.stats["ipopt_objective_evaluations"] = n_f;
    out.stats["ipopt_hessian_evaluations"] = n_h;
  } else if (!out.history.empty()) {
    out.iterations = out.history.back().iteration;
  }
  out.stats["ipopt_restoration_iterations"] = tnlp->restoration_iterations();
  out.stats["ipopt_warm_start"] = warm ? 1.0 : 0.0;
  if (!tnlp->notes().empty()) message += tnlp->notes() + ". ";
  out.message = message + "Ipopt: " + out.solver_status;
  return out;
}

}  // namespace ocpb
