// The problems OCPBench knows by name.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/field_sample.h"
#include "core/ocp.h"
#include "core/parameters.h"
#include "core/time_grid.h"
#include "core/types.h"

namespace ocpb {

/// A solution judged on the problem's *true* data, where the problem plans on an estimate of
/// it (the comm problems plan on a channel predicted from measurements; the truth is the
/// simulated realization): ProblemInfo::judge_on_truth. Numbers not computed are NaN.
struct TruthJudgement {
  std::string truth;                  ///< what the truth is ("true channel seed=3 cells=0.1m")
  double energy_true = NAN;           ///< Jbar of the executed controls on the truth
  double transmit_energy_true = NAN;  ///< its transmission part
  double J_true = NAN;                ///< energy_true + the terminal penalty
  double terminal_violation = NAN;    ///< max |psi_i| at the executed final state
  /// The executed path in the plane: its largest distance from the straight segment S-D, and
  /// its closest approach to the base station (m).
  double max_distance_from_segment = NAN;
  double min_distance_to_base = NAN;
};

/// A further published value of a problem beside its primary reference (ProblemInfo::
/// reference_value): typically a peer's optimum of one discretization at one grid
/// (CTBenchmarks' trapezoid objectives at N = 200, 500, 1000, 2000; COPS' values at its nh), which
/// OCPBench's transcription of the same scheme and grid must reproduce at the NLP level, or a
/// second continuous value from another source.
///
/// Written {value, quantity, scheme, intervals, source}, with the options as a sixth entry
/// where a value needs some (a default member initializer: the five-entry form stays free of
/// missing-initializer warnings).
struct ProblemReference {
  double value = NAN;
  std::string quantity = "J";         ///< "J" (the cost as posed) or "tf"
  std::string scheme = "continuous";  ///< "continuous", or the transcription whose NLP it solves
  int intervals = 0;                  ///< the grid of a discrete value (0 when continuous)
  std::string source;                 ///< where the value is published
  /// Ipopt options ("key", "value") this discrete value needs to be reproduced (as
  /// ProblemInfo::reference_options for the primary one); empty: OCPBench's defaults.
  std::vector<std::pair<std::string, std::string>> options = {};
};

/// The tags a problem may carry (`ocpbench list problems --tag T`), each with what it means.
struct ProblemTag {
  const char* name;
  const char* meaning;
};
/// Every tag, in the order the docs list them.
const std::vector<ProblemTag>& ProblemTags();
/// Throws std::invalid_argument "WHERE: unknown tag 'T' (the tags: a, b, ...)" unless `tag` is
/// one of ProblemTags().
void CheckProblemTag(const std::string& where, const std::string& tag);

/// A registered problem: how to build it, its parameters, and what is known about its optimum.
struct ProblemInfo {
  std::string name;
  std::string description;
  std::vector<ParameterSpec> parameters;
  /// Builds the problem. `seed` picks any random ingredient (a channel realization); problems
  /// without randomness ignore it.
  std::function<std::unique_ptr<Ocp>(const Parameters& params, std::uint64_t seed)> make;
  /// Optional: builds the problem with every check `make` runs, but without its expensive parts
  /// (comm-path2d, comm-fixed-path: the channel's options are checked and a path-loss stand-in
  /// replaces the simulated channel). `ocpbench run` validates a whole suite with it before
  /// anything runs, and uses the result only for its checks and sizes. Empty when `make` is
  /// cheap: validation then calls `make`.
  std::function<std::unique_ptr<Ocp>(const Parameters& params, std::uint64_t seed)> make_for_checks;
  int default_intervals = 100;            ///< the grid a suite uses when it names none
  std::optional<double> reference_value;  ///< published optimum of the cost below, if known
  std::string reference_quantity = "J";   ///< "J" (hard terminal form) or "tf" etc.
  std::string reference_source;           ///< where the reference value comes from
  /// What the reference value is an optimum of: "continuous" (the problem as posed in continuous
  /// time, comparable with any method's re-simulated cost), or the name of the discretization
  /// whose NLP at reference_intervals it solves (COPS' values: "trapezoid"), which only a record
  /// of that transcription and grid may be compared with.
  std::string reference_scheme = "continuous";
  int reference_intervals = 0;  ///< the grid of a discrete reference (0 when continuous)
  /// Ipopt options ("key", "value") a discrete primary reference needs to be reproduced
  /// (another barrier strategy where the NLP has several stationary points close together);
  /// empty: OCPBench's defaults. The NLP-level test adds them to a tight tol. An additional
  /// reference names its own (ProblemReference::options): what one grid needs, another may not
  /// (insurance: the adaptive barrier reproduces N = 200 and 1000, but not 500).
  std::vector<std::pair<std::string, std::string>> reference_options;
  /// Further published values (see ProblemReference); the primary one above is not repeated.
  std::vector<ProblemReference> additional_references;
  /// What kind of problem it is, from ProblemTags() (a registry test checks every name).
  std::vector<std::string> tags;
  /// Where the problem comes from (a suite, paper or book), when not the reference's source.
  std::string origin;
  bool uses_seed = false;  ///< true when `seed` changes the problem
  /// How the Hamiltonian descent applies (for example "path constraint as penalty rho max(0,
  /// c)^2, rho = 1e4"), or why it does not (then the note says "not applicable"); empty when it
  /// applies to the problem as stated. Shown by `ocpbench describe problem`. Whether it applies
  /// is decided by the problem itself (Ocp::HasHamiltonianMinimizer,
  /// Ocp::HamiltonianReformulation, Ocp::free_final_time), which the solver reads; a registry
  /// test checks that every note agrees with the solver's verdict.
  std::string hamiltonian_note;
  /// Optional: the optimal costate p*(t) (nx values, convention H = p^T f + L) of the problem
  /// at its default parameters, as posed (hard terminal form), on [t0, tf]. Records of cases
  /// that keep the defaults get a costate error against it (core/costate_error.h). Empty
  /// when unknown.
  std::function<Vec(double t)> reference_costate;
  /// Optional: a field to draw a solution over (comm-path2d: its channel map), kept in records
  /// that keep their trajectory (field s_map). Empty, or nullopt for a given problem: none.
  std::function<std::optional<FieldSample>(const Ocp& ocp)> sample_for_figures;
  /// Optional: judges controls on the problem's true data (see TruthJudgement): `controls`
  /// (nu x N, each interval's value) executed on `grid` from the problem's initial state, the
  /// problem built by `make(params, seed)`. Records of every solve carry the result
  /// (energy_true, ...). Empty, or nullopt for given parameters: nothing to judge.
  std::function<std::optional<TruthJudgement>(const Parameters& params,
                                              std::uint64_t seed,
                                              const Ocp& ocp,
                                              const TimeGrid& grid,
                                              const Mat& controls)>
      judge_on_truth;
};

/// Every registered problem, in a fixed order.
const std::vector<ProblemInfo>& Problems();
/// The problem called `name`; throws std::invalid_argument listing the valid names.
const ProblemInfo& FindProblem(const std::string& name);
/// Adds a problem defined outside OCPBench (see examples/user_example/) to the registry, after
/// the built-in ones. Throws std::invalid_argument when the name is empty or taken, or `make` is
/// empty. Call it before any solving starts (it is not synchronized with concurrent lookups);
/// it invalidates references previously returned by Problems() and FindProblem().
void RegisterProblem(ProblemInfo info);
/// Builds `name` with `assignments` ("key=value") applied over the defaults.
std::unique_ptr<Ocp> MakeProblem(const std::string& name,
                                 const std::vector<std::string>& assignments,
                                 std::uint64_t seed,
                                 Parameters* resolved = nullptr);

}  // namespace ocpb
