// Ipopt on an OCPBench Nlp: options, status names and the solve call. The only file that includes
// Ipopt's headers is ipopt_adapter.cc.
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/nlp.h"
#include "core/option_schema.h"
#include "core/solve_result.h"
#include "solvers/nlp_solve.h"

namespace ocpb {

/// The value type of an Ipopt option, as Ipopt registers it.
enum class IpoptOptionType { kNumber, kInteger, kString };

/// One entry of OCPBench's table of Ipopt (3.11) options that may be passed through.
struct IpoptOptionSpec {
  IpoptOptionSpec(std::string name_, IpoptOptionType type_, std::vector<std::string> values_ = {})
      : name(std::move(name_)), type(type_), values(std::move(values_)) {}

  std::string name;
  IpoptOptionType type = IpoptOptionType::kNumber;
  /// String options: the values Ipopt accepts (empty: any string, e.g. a file name).
  std::vector<std::string> values;
  /// Number and integer options: the range the linked Ipopt registers for the option (read
  /// from its registry, so that a value Ipopt would refuse at solve time is refused when the
  /// options are checked, before any work).
  OptionBounds bounds;
  /// Number and integer options: the linked Ipopt's default (NaN when it registers none).
  double default_value = std::numeric_limits<double>::quiet_NaN();
};

/// A rule of Ipopt that ties two options: `low` may not exceed `high` (mumps_pivtol <=
/// mumps_pivtolmax, min_refinement_steps <= max_refinement_steps, ...). Ipopt checks these only
/// when it builds its algorithm, after the work before the solve; OCPBench checks them with the
/// options (IpoptOptions::IsValid), an unset option taking Ipopt's default.
struct IpoptOrderedPair {
  const char* low;
  const char* high;
};
/// Whether the linked Ipopt's registry accepts `v` (its name, type and value: what Ipopt's
/// OptionsList would say when the solve starts); false with "ipopt option 'NAME': ..." in
/// `error` otherwise.
struct IpoptOptionValue;
bool IpoptRegistryAccepts(const IpoptOptionValue& v, std::string* error);

/// Rules of this kind known of Ipopt 3.11. The check does not use this list (it asks Ipopt,
/// IpoptAcceptsTogether); the option tests try each rule against the check and a solve.
const std::vector<IpoptOrderedPair>& IpoptOrderedPairs();

/// Whether the linked Ipopt accepts `options` together, asked of Ipopt itself: an
/// IpoptApplication given the settings a solve gives it (IpoptSettings' list: the fields, the
/// pass-through options; without output_file, whose place is checked as any output's, and with
/// print_level 0) starts on a two-variable NLP and stops after three iterations, once for each
/// start a solve may make (exact and limited-memory Hessian, cold and warm). Ipopt checks the
/// rules that tie options (mumps_pivtol <= mumps_pivtolmax, min_refinement_steps <=
/// max_refinement_steps, mehrotra_algorithm's requirements, ...) when it builds its algorithm
/// and takes its first steps (alpha_for_y=acceptor outside the penalty line searches), so such
/// rules of the linked Ipopt are seen without a list of them; a rule Ipopt checks only in a
/// part that a three-iteration solve of this NLP does not reach (its restoration phase) is not.
/// False with Ipopt's own reason in `error` ("the linked Ipopt refuses these options together:
/// Option \"mumps_pivtolmax\": This value must be between mumps_pivtol and 1 (Ipopt's rule,
/// checked before any work)"). Each list of settings is asked once per process (a few ms);
/// options without a pass-through setting (OCPBench's fields only) are not asked (no rule ties
/// two of them: the option tests try their combinations against Ipopt).
struct IpoptOptions;
bool IpoptAcceptsTogether(const IpoptOptions& options, std::string* error);

/// The pass-through table: the Ipopt options OCPBench lets a request set, with their types.
/// IpoptOptionTableMatchesIpopt() checks it against Ipopt's own registry.
const std::vector<IpoptOptionSpec>& IpoptOptionTable();
/// The table entry for `name`, or nullptr.
const IpoptOptionSpec* FindIpoptOption(const std::string& name);
/// True when every table entry is registered by the linked Ipopt with the same type (and, for
/// strings, every listed value is one Ipopt accepts); otherwise false with the mismatches in
/// `error`.
bool IpoptOptionTableMatchesIpopt(std::string* error);

/// One typed Ipopt option setting.
struct IpoptOptionValue {
  std::string name;
  IpoptOptionType type = IpoptOptionType::kNumber;
  double number = 0.0;
  int integer = 0;
  std::string text;
};

/// Options of the Ipopt backend (Wächter & Biegler, "On the implementation of an interior-point
/// filter line-search algorithm for large-scale nonlinear programming", Math. Prog. 106, 2006).
/// Every field is passed to Ipopt under its own name; defaults are OCPBench's, not always Ipopt's
/// (marked "Ipopt default" where they agree).
struct IpoptOptions {
  // ---- termination --------------------------------------------------------------
  /// Converged when the scaled NLP error (max of dual infeasibility, constraint violation and
  /// complementarity, scaled) is <= tol and the unscaled ones are below their own tolerances.
  /// Ipopt default.
  double tol = 1e-8;
  /// Iteration limit; reaching it gives SolveStatus::kMaxIterations. Ipopt default.
  int max_iter = 3000;
  /// "Acceptable" level: acceptable_iter consecutive iterates with error <= acceptable_tol end
  /// the solve with Solved_To_Acceptable_Level. Ipopt default.
  double acceptable_tol = 1e-6;
  int acceptable_iter = 15;
  /// CPU time limit in seconds (Ipopt's max_cpu_time); reaching it gives kMaxTime.
  double max_cpu_time = 1e6;
  // ---- algorithm ----------------------------------------------------------------
  /// "monotone" (Fiacco-McCormick, Ipopt default) or "adaptive".
  std::string mu_strategy = "monotone";
  /// "auto" (OCPBench): "exact" when the Nlp HasHessian(), else "limited-memory". "exact" on an
  /// Nlp without a Hessian is replaced by "limited-memory" and said so in the result's message.
  std::string hessian_approximation = "auto";
  /// Only "mumps" is available in OCPBench's build (no HSL).
  std::string linear_solver = "mumps";
  /// MUMPS' fill-reducing ordering (Ipopt's mumps_pivot_order, ICNTL(7): 0 AMD, 2 AMF, 3 SCOTCH,
  /// 4 PORD, 5 METIS, 6 QAMD, 7 MUMPS' automatic choice, Ipopt's default). -1 (OCPBench's
  /// default) chooses by problem class, as measured (solvers/README-nlp.md, "MUMPS ordering"):
  /// 0 (AMD) when the NLP has an exact Hessian (the collocation transcriptions: on comm-path2d
  /// at N = 400, 12-21 % fewer MUMPS instructions than 7 with the same iterates), 7 otherwise
  /// (limited-memory, single shooting: not measured, Ipopt's default kept).
  /// `--option mumps_pivot_order=K` overrides it (applied after this field).
  int mumps_pivot_order = -1;
  // ---- scaling ------------------------------------------------------------------
  /// "gradient-based" (Ipopt default: scale f and each g_i so their gradient at the start has
  /// max-norm <= nlp_scaling_max_gradient), "none", or "equilibration-based" (needs MC19, absent).
  std::string nlp_scaling_method = "gradient-based";
  /// Ipopt minimizes obj_scaling_factor * f (on top of nlp_scaling_method). Ipopt default.
  double obj_scaling_factor = 1.0;
  /// Largest gradient max-norm gradient-based scaling leaves alone. Ipopt default.
  double nlp_scaling_max_gradient = 100.0;
  // ---- warm start: only for a solve given starting multipliers (SolveNlpWithIpopt's y0,
  // mesh refinement's 2nd.. meshes with mesh_warm_multipliers); Ipopt's
  // warm_start_init_point=yes. Defaults chosen on mesh refinement of results/mesh's problems
  // (results/mesh/warm-multipliers.md, README "Adaptive mesh refinement"). -----------------
  /// Ipopt's warm_start_bound_push, also used for warm_start_bound_frac (at most 0.5),
  /// warm_start_slack_bound_push and warm_start_slack_bound_frac: how far a starting variable
  /// (slack) at or outside a bound is pushed into the interior, absolutely and relative to the
  /// bounds' distance. 1e-6: on results/mesh/warm-multipliers.md's cases as many or fewer
  /// Ipopt iterations than 1e-9 on each (fewer on bryson-denham and goddard); Ipopt's default
  /// 1e-3 took 3.5x as many on goddard with Hermite-Simpson. > 0.
  double warm_start_bound_push = 1e-6;
  /// Ipopt's warm_start_mult_bound_push: the given bound multipliers (and the slacks' of
  /// inequality rows) are raised to at least this. 1e-9: 1e-6 and Ipopt's default 1e-3 took
  /// as many or more iterations on each case (1e-3: 3.7x on robot-arm with LGR). > 0.
  double warm_start_mult_bound_push = 1e-9;
  /// The barrier parameter a warm-started solve begins with (Ipopt's mu_init, for that solve
  /// only; a pass-through mu_init applies to cold starts). Ipopt's default 0.1 would first
  /// solve a barrier problem far from the given point's complementarity. 1e-12: as many or
  /// fewer iterations than 1e-6, 1e-8 and 1e-10 on each case; 1e-14 took 4x more on goddard with
  /// Hermite-Simpson. > 0.
  double warm_start_mu_init = 1e-12;
  // ---- output -------------------------------------------------------------------
  /// 0 = silent (OCPBench's default), 5 = Ipopt's usual iteration log, up to 12.
  int print_level = 0;
  /// Any other option from IpoptOptionTable(), applied after the fields above.
  std::vector<IpoptOptionValue> extra;

  /// True when every field is in range (Schema()'s rules: tol > 0, max_iter >= 0, ...,
  /// obj_scaling_factor finite and nonzero) and every extra option is in the table with its
  /// type; otherwise false with a one-line reason in `error`.
  bool IsValid(std::string* error) const;
  /// Every key a request may set: the fields above by name and every option of
  /// IpoptOptionTable() (unset: Ipopt's own default), with types and rules.
  static const OptionSchema& Schema();
  /// `base` with `options` applied (resolved by Schema(): unknown keys refused listing the
  /// valid ones, values by type), then IsValid. Throws std::invalid_argument.
  static IpoptOptions Apply(const OptionMap& options, IpoptOptions base);
};

/// Ipopt's name for an ApplicationReturnStatus value ("Solve_Succeeded", "Restoration_Failed",
/// ...), or "Unknown_Status(<code>)".
std::string IpoptStatusName(int application_return_status);
/// OCPBench's grouping of an ApplicationReturnStatus value:
///   Solve_Succeeded, Feasible_Point_Found          -> kConverged
///   Solved_To_Acceptable_Level                     -> kAcceptable
///   Infeasible_Problem_Detected                    -> kInfeasible
///   Search_Direction_Becomes_Too_Small             -> kStepTooSmall
///   Maximum_Iterations_Exceeded                    -> kMaxIterations
///   Maximum_CpuTime_Exceeded                       -> kMaxTime
///   Diverging_Iterates, Restoration_Failed, Error_In_Step_Computation,
///   Invalid_Number_Detected                        -> kNumericalFailure
///   Not_Enough_Degrees_Of_Freedom, Invalid_Problem_Definition, Invalid_Option -> kInvalidInput
///   User_Requested_Stop, Unrecoverable_Exception, NonIpopt_Exception_Thrown,
///   Insufficient_Memory, Internal_Error, unknown  -> kError
SolveStatus MapIpoptStatus(int application_return_status);
/// Every ApplicationReturnStatus value Ipopt 3.11 defines.
std::vector<int> AllIpoptStatusCodes();

/// Runs Ipopt on `nlp` from `z0` (size num_variables()) and, when `y0` is not empty, from the
/// multipliers y0 too (Ipopt's warm_start_init_point=yes with the options' warm_start_* fields
/// and warm_start_mu_init; Ipopt clips them to its own rules: bound multipliers raised to
/// warm_start_mult_bound_push, those of inequality rows' slacks likewise). Never throws for
/// anything Ipopt or the Nlp does: failures come back as the solution's status. Fills z, lambda
/// (Ipopt's constraint multipliers), z_lower, z_upper (its bound multipliers), the objective,
/// Ipopt's iteration count, a history row per iteration from Ipopt's intermediate callback
/// (objective, primal and dual infeasibility as in Ipopt's iteration log, CPU seconds since the
/// call started), and stats: ipopt_cpu_seconds, ipopt_wall_seconds (Ipopt's SolveStatistics),
/// ipopt_dual_inf, ipopt_constr_viol, ipopt_complementarity, ipopt_kkt_error (unscaled),
/// ipopt_objective_evaluations, ipopt_hessian_evaluations, ipopt_exact_hessian (1 or 0),
/// ipopt_warm_start (1 when y0 was used, else 0). Throws std::invalid_argument only when `options`
/// is not valid (IsValid), z0 has the wrong size, or y0 is not empty and does not fit the NLP
/// (NlpMultipliers::Fits).
NlpSolution SolveNlpWithIpopt(const Nlp& nlp,
                              const Vec& z0,
                              const IpoptOptions& options,
                              const NlpMultipliers& y0 = NlpMultipliers());
/// SolveNlpWithIpopt without OCPBench's own check of the options (IpoptOptions::IsValid): what
/// Ipopt itself makes of them, for the tests that compare the check with Ipopt (a refused
/// setting comes back as kInvalidInput with solver_status "Invalid_Option").
NlpSolution SolveNlpWithIpoptUnchecked(const Nlp& nlp,
                                       const Vec& z0,
                                       const IpoptOptions& options,
                                       const NlpMultipliers& y0 = NlpMultipliers());

}  // namespace ocpb
