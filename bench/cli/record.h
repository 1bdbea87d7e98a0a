// The result record: one struct from which every record is written and into which every record
// is read (summary, merge, resume, compare). Its JSON form is a contract, documented once, in
// results/record.schema.json (JSON Schema) and the README.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/solve_result.h"
#include "core/types.h"

namespace ocpb {

/// The version of the record format written by this build. 1: records before the typed record
/// (they carry no schema_version); 2: the typed record (adds schema_version, solver_options,
/// transcription_options); 3: adds warnings, discretization_gap, stopping_tolerance,
/// continuation and trajectory.own (the method's own states and costates, a warm start's
/// source); later within 3, optional history[i].intervals (an iterate on a grid-sequenced solve's
/// coarser grid). Readers take all three (fields a version lacks keep their defaults).
inline constexpr int kRecordSchemaVersion = 3;

/// The trajectory a record keeps (for figures): t (N + 1 grid points), states x (nx rows of
/// N + 1), controls u (nu rows of N: each interval's left end) and the rule that says how u
/// reads between samples.
struct RecordTrajectory {
  std::vector<double> t;
  Mat x;
  Mat u;
  std::string u_rule;
  /// The method's own states (and costates, where it has them) on its own state grid: what a
  /// warm start from this record takes (`--initial-guess`). Empty when the method carries no
  /// states (the Hamiltonian descent's are the evaluator's, single shooting has none).
  std::vector<double> own_t;
  Mat own_x;
  Mat own_p;  ///< empty when the method has no costates
};

/// Something about the result that its status does not say (JudgeWarning: a stable code and a
/// one-line message).
struct RecordWarning {
  std::string code;
  std::string message;
};

/// The option that stops the solver and bounds its accuracy, as used (SolverInfo).
struct RecordStoppingTolerance {
  std::string option;
  double value = NAN;
  std::string note;
};

/// A solve that started from an earlier stage (CaseSpec::continuation): that stage's outcome.
/// The record's own status, iterations and history are the final stage's; cpu_seconds counts
/// both stages.
struct RecordContinuation {
  std::string from;  ///< "penalty": the penalty form solved first, its solution the start
  std::string status, solver_status, message;
  int iterations = -1;
  double cpu_seconds = NAN;
};

/// An adaptive mesh refinement (transcription option mesh_tolerance > 0): why it stopped, the
/// final mesh's nodes (nominal horizon; the grid the evaluator judged on, stretched to the
/// record's final_time for a free final time) and one row per mesh solved (SolveResult).
struct RecordMesh {
  std::string stop_reason;
  std::vector<double> nodes;
  std::vector<MeshIterationRecord> history;
};

/// A method's costates as a record keeps them (with its trajectory): the times of the method's
/// own costate grid (for Hermite-Simpson and LGR its interior points too) and p (nx rows).
struct RecordCostates {
  std::vector<double> t;
  Mat p;
};

/// A published optimum the record is compared with: value, quantity ("J", "tf"), source, the
/// problem it is an optimum of ("continuous", or a scheme's name whose NLP at N it solves).
struct RecordReference {
  double value = NAN;
  std::string quantity = "J";
  std::string source;
  std::string scheme = "continuous";
  int N = 0;  ///< the grid of a discrete reference (0 when continuous)
};

/// A solve judged on the problem's true data (ProblemInfo::judge_on_truth; the comm problems:
/// the simulated channel realization the planner only knows through its prediction): the
/// method's controls executed with forward Euler on the record's grid, their energy there, and
/// the executed path's geometry. Online records carry their own energy_true etc. (OnlineOutcome).
struct RecordTruth {
  std::string model;  ///< what the truth is ("true channel seed=3 cells=0.1m")
  double energy_true = NAN, transmit_energy_true = NAN, J_true = NAN;
  double max_distance_from_segment = NAN;  ///< m, the executed path from the segment S-D
  double min_distance_to_base = NAN;       ///< m, its closest approach to the base station
};

/// What built the record.
struct RecordVersions {
  std::string ocpbench, commit, compiler, ipopt, nlopt;
};

/// The fields of an online re-planning record (kind "online"): energies of the executed and
/// the offline trajectory on the true channel, and the bulky parts as JSON (cycles, executed,
/// offline and measurements; the scenario's resolved settings).
struct OnlineOutcome {
  nlohmann::json settings = nlohmann::json::object();  ///< resolved scenario settings
  std::map<std::string, std::string> replan_options;   ///< solver options of the re-plans
  nlohmann::json cycles = nlohmann::json::array();     ///< one object per re-planning cycle
  double energy_true = NAN, energy_predicted = NAN, J_true = NAN;
  double transmit_energy_true = NAN, offline_transmit_energy_true = NAN;
  double transmit_energy_ratio = NAN, energy_ratio = NAN;
  double offline_energy_true = NAN, offline_energy_predicted = NAN, offline_J_true = NAN;
  double offline_terminal_violation = NAN, offline_solve_seconds = NAN;
  std::vector<double> offline_terminal_residual;
  /// With keep_trajectory: {t, x, u} executed and offline, {x, y, cycle} of the measurements;
  /// null otherwise.
  nlohmann::json executed, offline, measurements;
};

/// One case's record. Numbers that were not computed are NaN (JSON null); counts that were not
/// computed are -1.
struct Record {
  int schema_version = kRecordSchemaVersion;
  std::string kind = "solve";  ///< "solve" or "online"
  std::string key;             ///< the case's stable identifier (CaseSpec::Key)

  // ---- the case ----------------------------------------------------------------------------
  std::string problem;
  std::map<std::string, std::vector<double>> parameters;  ///< every parameter, resolved
  std::uint64_t seed = 1;
  bool uses_seed = false;
  std::string solver, transcription, algorithm;
  int N = 0;
  std::optional<int> degree;  ///< transcriptions with a "degree" option (LGR)
  std::string terminal = "penalty", integrator = "euler", evaluated_with = "euler";
  /// The options as the case gave them (canonical text), and every option the solve used with
  /// its effective value (defaults included), by owner.
  std::map<std::string, std::string> options;
  nlohmann::json solver_options = nlohmann::json::object();
  nlohmann::json transcription_options = nlohmann::json::object();
  std::optional<std::string> initial_guess;
  int repeats = 1;

  // ---- how it ended --------------------------------------------------------------------------
  std::string status, solver_status, message;
  double objective = NAN;
  int iterations = -1;
  double cpu_seconds = NAN;
  std::vector<double> cpu_seconds_repeats;
  double wall_seconds = NAN;
  std::map<std::string, double> solver_stats;
  std::vector<IterationRecord> history;

  // ---- the common evaluator ------------------------------------------------------------------
  double J = NAN, Jbar = NAN;
  double terminal_violation = NAN, control_violation = NAN, path_violation = NAN;
  std::vector<double> terminal_residual, final_state;
  double J_fine = NAN, Jbar_fine = NAN, terminal_violation_fine = NAN;
  double resimulation_defect = NAN;
  double final_time = NAN;  ///< the horizon the controls were judged on
  /// A free initial state (Ocp::HasFreeInitialState): the x(t0) the method chose and the judge
  /// started from; empty (left out) otherwise.
  std::vector<double> initial_state;
  /// A problem with static parameters: their optimal values (initial_state's last
  /// Ocp::num_static_parameters() entries); empty (left out) otherwise.
  std::vector<double> static_parameters;
  /// A problem with state bounds or a free initial state: the fine re-simulation's
  /// Evaluation::state_bound_violation; unset (left out) otherwise.
  std::optional<double> state_bound_violation;
  /// A problem with boundary constraints: the fine re-simulation's b(x(t0), x(tf)) and its
  /// Evaluation::boundary_violation; empty / unset (left out) otherwise.
  std::vector<double> boundary_residual;
  std::optional<double> boundary_violation;
  bool final_time_free = false;
  /// |objective - fine| / max(|objective|, |fine|, 1e-8), fine = J_fine (penalty form) or
  /// Jbar_fine (hard form): how far the method's own discrete problem is from the continuous one
  /// at its answer (Judgement::discretization_gap).
  double discretization_gap = NAN;
  std::vector<RecordWarning> warnings;
  std::optional<RecordStoppingTolerance> stopping_tolerance;
  std::optional<RecordContinuation> continuation;
  std::optional<RecordMesh> mesh;

  /// Costates: where the method's come from (SolveResult::costate_source; empty: it has none),
  /// their error against the problem's known optimal costate (RelativeCostateError; NaN when
  /// not compared), and, with the trajectory, the costates themselves.
  std::string costate_source;
  double costate_error = NAN;
  std::optional<RecordCostates> costates;

  std::optional<RecordTrajectory> trajectory;
  nlohmann::json s_map;  ///< null, or the channel map for figures
  std::optional<RecordReference> reference;
  /// A peer's published optimum of the very NLP this record solved (ProblemInfo::
  /// additional_references with the record's transcription and N, e.g. CTBenchmarks' trapezoid
  /// value at N = 200): the transcription is checked against it at the NLP level (objective).
  std::optional<RecordReference> nlp_reference;
  std::optional<OnlineOutcome> online;
  std::optional<RecordTruth> truth;  ///< solve records of problems with judge_on_truth
  RecordVersions versions;

  /// The JSON object (schema results/record.schema.json). Fields that do not apply (online
  /// parts of a solve record, an absent trajectory, reference or degree, costate fields a method
  /// or problem does not have) are left out.
  nlohmann::json ToJson() const;
  /// Reads a record. Fields missing from older records keep their defaults; a field of the
  /// wrong type throws std::invalid_argument "FIELD: must be ..." (the caller adds file and
  /// line). Keys it does not know are ignored (derived fields of derived.jsonl).
  static Record FromJson(const nlohmann::json& j);
  /// The same, moving the bulky parts (s_map, the online cycles and paths, the effective
  /// options) out of `j` instead of copying them.
  static Record FromJson(nlohmann::json&& j);

 private:
  static Record Read(const nlohmann::json& j, nlohmann::json* movable);
};

/// The versions of this build (OCPBench, commit, compiler, Ipopt, NLopt).
RecordVersions CurrentVersions();

}  // namespace ocpb
