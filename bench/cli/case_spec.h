// One benchmark case: what to solve and how (`ocpbench solve`'s flags, one case of a suite).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/integrator.h"
#include "core/ocp.h"
#include "core/option_value.h"

namespace ocpb {

/// What to solve and how. Defaults are what `ocpbench solve` uses when an option is omitted.
struct CaseSpec {
  std::string problem;           ///< registry name
  std::vector<std::string> set;  ///< parameter overrides, "key=value" or "key=v1,v2"
  std::uint64_t seed = 1;        ///< channel realization (problems that use one)
  std::string solver;            ///< registry name
  std::string transcription;     ///< NLP solvers only
  /// Another spelling of the solver's option "algorithm" (NLopt's; `--algorithm`, a suite's
  /// "algorithm"): ResolveCase moves it into `options`, where an entry of the same key must
  /// agree. Refused for a solver without the option.
  std::string algorithm;
  int intervals = 0;  ///< N; 0: the problem's default grid
  /// Another spelling of the transcription's option "degree" (LGR's; `--degree`, a suite's
  /// "degree"): ResolveCase moves it into `options` when the transcription has the option
  /// (an entry of the same key must agree) and drops it otherwise.
  int degree = kDefaultDegree;
  /// Whether `degree` was given: without it, an option "degree" in `options` is the degree and
  /// the field's default gives way.
  bool degree_given = false;
  TerminalMode terminal = TerminalMode::kPenalty;
  Integrator integrator = Integrator::kEuler;  ///< the method's own integrator (Hamiltonian)
  /// The common evaluator's integrator on the method's grid. Every record also carries the
  /// RK4 evaluation on a 10x finer grid (the "fine" fields).
  Integrator evaluate_with = Integrator::kEuler;
  /// The method's options: each key is the solver's (SolverInfo::options) or, failing that,
  /// the transcription's (TranscriptionInfo::options). Text values are read by the option
  /// grammar; ResolveCase turns them into typed values once (and moves `algorithm` and
  /// `degree` here).
  OptionMap options;
  int repeats = 1;              ///< timing repeats; the record keeps the median CPU time
  bool keep_trajectory = true;  ///< store t, x, u in the record (for figures)
  /// A previous `ocpbench solve --json` record whose controls start the solve (empty: the
  /// solver's default start). Read and checked before solving (bench/cli/initial_guess.h).
  std::string initial_guess;
  /// "" (none) or "penalty": solve the penalty form first and start the hard form from its
  /// solution (SolveHardFromPenalty, solvers/continuation.h); needs terminal = hard.
  std::string continuation;
  /// "solve" (one solve, the default) or "online" (re-planning with channel updates, paper
  /// Section IV: `options` are the solver options of every solve, `replan_options` override them
  /// for the re-plans, `online` holds the scenario settings (OnlineScenarioSchema)).
  std::string kind = "solve";
  OptionMap online;          ///< kind "online": scenario settings
  OptionMap replan_options;  ///< kind "online": re-plan solver options

  /// The default of `degree`: LGR's own default degree.
  static constexpr int kDefaultDegree = 3;

  /// A stable identifier of the case (for --resume, shards and compare): every field that
  /// changes the result, options by their canonical text (ResolveCase). The options "algorithm"
  /// and "degree" keep the places their case fields have always had in the key ("|LD_MMA|",
  /// "deg=5"), whichever spelling gave them.
  std::string Key() const;
  /// `options` without the ones a record and the key show in their own fields ("algorithm",
  /// "degree": Record::algorithm and Record::degree).
  OptionMap OptionsBesideCaseFields() const;
  /// The spec's own fields: throws std::invalid_argument naming the field when a value is out
  /// of range. ValidateCase checks everything else that can be checked without solving.
  void Validate() const;
};

/// A method's options split by owner, each resolved by its schema.
struct MethodOptions {
  OptionMap solver;
  OptionMap transcription;
};

/// The case's options (with `algorithm` and `degree`) split between the solver and its
/// transcription and resolved. Throws std::invalid_argument "options: ..." for a key neither
/// knows (listing both sets of valid keys) or a value that breaks its rule, and
/// "algorithm: ..." when the solver has no option "algorithm".
MethodOptions ResolveMethodOptions(const CaseSpec& spec);

/// `spec` in canonical form: `algorithm` and `degree` moved into `options` (the field
/// `algorithm` emptied, `degree` back at its default), every option, online setting and
/// re-plan option resolved to its typed value (so that Key() shows canonical values). With
/// `method`, also the options split by owner (ResolveMethodOptions, without resolving them
/// twice). Throws std::invalid_argument as ResolveMethodOptions, and for unknown solvers or
/// transcriptions.
CaseSpec ResolveCase(CaseSpec spec, MethodOptions* method = nullptr);

/// The fields of one suite case, read in place from the suite document (never copied out of
/// it): the method's own fields over its group's, and the seed and N the case takes from the
/// group's lists. A view: the document must outlive it.
class CaseFields {
 public:
  /// One JSON object's fields (the C++ API, a test).
  explicit CaseFields(const nlohmann::json& fields) : method_(&fields) {}
  /// A suite case: `method` over `group` (whose "methods", "seeds" and "N" are not case
  /// fields), with `seed` and `n` (nullptr: none) from the group's lists.
  CaseFields(const nlohmann::json& method,
             const nlohmann::json& group,
             const nlohmann::json* seed,
             const nlohmann::json* n)
      : method_(&method), group_(&group), seed_(seed), n_(n) {}

  /// The value of field `key`, or nullptr when the case does not give it.
  const nlohmann::json* Find(const std::string& key) const;
  /// Every field the case gives, each once, sorted.
  std::vector<std::string> Keys() const;

 private:
  const nlohmann::json* method_;
  const nlohmann::json* group_ = nullptr;
  const nlohmann::json* seed_ = nullptr;
  const nlohmann::json* n_ = nullptr;
};

/// Parses one suite case strictly and resolves it (ResolveCase): unknown keys, wrong types,
/// null values (omit a key for its default) and invalid values throw std::invalid_argument
/// "FIELD: rule" prefixed by `where`.
CaseSpec ParseCaseSpec(const CaseFields& fields, const std::string& where);
/// The same for one JSON object holding every field of the case.
CaseSpec ParseCaseSpec(const nlohmann::json& j, const std::string& where);

/// "penalty" or "hard"; std::invalid_argument otherwise.
TerminalMode ParseTerminal(const std::string& text);

/// A seed written as text (`--seed`): decimal digits only, 0 to 2^64 - 1 =
/// 18446744073709551615, never wrapped (-1) or saturated (1e30). Throws std::invalid_argument
/// "FIELD: must be an integer from 0 to 18446744073709551615 (got 'TEXT')".
std::uint64_t ParseSeed(const std::string& text, const std::string& field);
/// The same rule for a seed in a suite file (a JSON integer).
std::uint64_t SeedFromJson(const nlohmann::json& value, const std::string& field);

}  // namespace ocpb
