// The transcriptions OCPBench knows by name, with their options.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/option_binding.h"
#include "core/option_schema.h"
#include "transcriptions/transcription.h"

namespace ocpb {

/// A registered transcription: how to build it, its options, and its size per interval.
struct TranscriptionInfo {
  std::string name;
  std::string description;
  std::function<std::unique_ptr<Transcription>()> make;
  /// Its options (keys, defaults, rules), for example LGR's "degree" and the scaling keys
  /// "objective_scale", "state_scale", "control_scale" (`ocpbench describe transcription`).
  OptionSchema options;
  /// Writes resolved `options` into the fields of a TranscriptionOptions (degree, scaling, ...).
  /// Throws std::invalid_argument for an unknown key or a broken rule. Empty: the
  /// transcription takes no options.
  std::function<void(const OptionMap& options, TranscriptionOptions* out)> configure;
  /// Collocation points per interval (NLP nodes = N * points + 1) under `options`: the memory
  /// estimate's size model. Empty: 1.
  std::function<int(const TranscriptionOptions& options)> points_per_interval;
  /// Whether its NLP can make a free final time a variable (Ocp::free_final_time()); the
  /// NLP solvers report kNotApplicable otherwise.
  bool takes_free_final_time = true;
  /// Whether its NLP makes x(t0) a decision within Ocp::initial_state_bounds() (and adds the
  /// initial cost); the NLP solvers report kNotApplicable otherwise.
  bool takes_free_initial_state = true;
  /// Whether its NLP takes Ocp::state_bounds() (as bounds of its state variables); the NLP
  /// solvers report kNotApplicable otherwise.
  bool takes_state_bounds = true;
  /// Whether its NLP takes Ocp::num_boundary() boundary constraints b(x(t0), x(tf)) as rows;
  /// the NLP solvers report kNotApplicable otherwise.
  bool takes_boundary_constraints = true;

  /// A TranscriptionOptions with `options` applied over the defaults (configure).
  TranscriptionOptions Configure(const OptionMap& options) const;
  /// points_per_interval of Configure(options), or 1.
  int PointsPerInterval(const OptionMap& options) const;
};

/// Every registered transcription: the built-in ones, then RegisterTranscription's.
const std::vector<TranscriptionInfo>& Transcriptions();
/// Throws std::invalid_argument listing the valid names when `name` is unknown.
const TranscriptionInfo& FindTranscription(const std::string& name);
/// Adds a transcription defined outside OCPBench. Throws std::invalid_argument when the name is
/// empty or taken, or `make` is empty. Call it at start-up, before any solving (it invalidates
/// references returned by Transcriptions() and FindTranscription()).
void RegisterTranscription(TranscriptionInfo info);

/// Declares on `binding` the options every built-in scheme shares: the NlpScaling keys
/// objective_scale (number > 0), state_scale and control_scale (lists of numbers > 0, one per
/// component; empty: all ones). For a transcription written outside OCPBench that honours
/// TranscriptionOptions::scaling too.
void BindScalingOptions(OptionBinding<TranscriptionOptions>* binding);
/// Which mesh refinement a scheme does: h (fixed order: split intervals) or ph (LGR: raise the
/// degree or split).
enum class MeshRefinementKind { kH, kPh };
/// Declares on `binding` the adaptive mesh refinement options (TranscriptionOptions::mesh):
/// mesh_tolerance (number >= 0, default 0 = off), mesh_max_iterations (integer >= 1, default
/// 10), mesh_max_nodes (integer >= 2, default 2000), mesh_estimate (the scheme's own estimate,
/// "defect" for h and "interpolation" for ph, or "simulation"), mesh_warm_multipliers (bool,
/// default true); for h also mesh_max_new_points
/// (integer >= 1, default 5), for ph mesh_min_degree (default 3), mesh_max_degree (default 10;
/// both in [1, 59], min <= max) and mesh_reduce (default true). For schemes whose
/// TranscribedNlp has IntervalErrors (trapezoid, hermite-simpson: h; lgr: ph).
void BindMeshOptions(OptionBinding<TranscriptionOptions>* binding, MeshRefinementKind kind);
/// A TranscriptionInfo whose `options` and `configure` come from `binding`.
TranscriptionInfo MakeTranscriptionInfo(
    std::string name,
    std::string description,
    std::function<std::unique_ptr<Transcription>()> make,
    OptionBinding<TranscriptionOptions> binding,
    std::function<int(const TranscriptionOptions&)> points_per_interval = nullptr);

}  // namespace ocpb
