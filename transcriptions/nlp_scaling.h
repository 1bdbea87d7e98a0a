// Deliberate scaling of a transcribed NLP: objective factor and per-component variable scales.
#pragma once

#include <string>

#include "core/types.h"

namespace ocpb {

/// The scaling hook of OCPBench's direct transcriptions. The NLP a solver sees is
///
///   minimize  objective * J(D zhat)   subject to   R g(D zhat) in [R g_l, R g_u],
///
/// where the physical variables are z = D zhat: every state component i is stored as
/// x_i / state[i] and every control component j as u_j / control[j]. The defect rows of state
/// component i are multiplied by R_ii = 1 / state[i] (a defect has the units of its state), so a
/// well-chosen `state` makes both the variables and the defects O(1). Path, control-set and
/// terminal rows are not scaled. Bounds, starting point, derivatives and multipliers are all
/// transformed accordingly; Controls(), States() and Costates() always return physical values
/// (costates in units of J per unit of state, whatever `objective` is).
///
/// Why a hook: the paper's communication-aware problem mixes cost terms of very different sizes
/// (transmit power ~1e-5 W next to a motion power of ~10 W), see the project notes, and
/// automatic gradient-based scaling in the solver does not fix the conditioning of the penalty.
/// The defaults (all ones) leave the NLP unscaled.
struct NlpScaling {
  /// The objective is multiplied by this factor (> 0, finite). Default 1.
  double objective = 1.0;
  /// Per-state-component scales (size nx, each > 0 and finite), or empty for all ones.
  Vec state;
  /// Per-control-component scales (size nu, each > 0 and finite), or empty for all ones.
  Vec control;

  /// True when every field satisfies its rule above (sizes are checked against the problem
  /// separately, by IsValidFor); otherwise false with a one-line reason in *error.
  bool IsValid(std::string* error) const;
  /// IsValid() and, when non-empty, state.size() == nx and control.size() == nu.
  bool IsValidFor(int nx, int nu, std::string* error) const;
  /// True when this scaling changes nothing (objective 1, all scales 1 or empty).
  bool IsIdentity() const;
};

}  // namespace ocpb
