// Transcriptions: an Ocp on a grid becomes an Nlp, and an NLP solution becomes controls again.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/control_trajectory.h"
#include "core/integrator.h"
#include "core/nlp.h"
#include "core/ocp.h"
#include "core/time_grid.h"
#include "transcriptions/mesh_refinement.h"
#include "transcriptions/multiplier_trajectories.h"
#include "transcriptions/nlp_scaling.h"

namespace ocpb {

/// An Nlp that knows the optimal-control meaning of its variables.
class TranscribedNlp : public Nlp {
 public:
  /// The controls encoded in z, with the interpolation rule of this transcription; this is
  /// what the common evaluator judges.
  virtual ControlTrajectory Controls(ConstVecRef z) const = 0;
  /// The grid on which States() and Costates() are given, at the problem's (nominal) horizon.
  virtual const TimeGrid& state_grid() const = 0;
  /// True when the final time is one of the NLP's variables (the problem's free final time).
  virtual bool HasFinalTimeVariable() const { return false; }
  /// The final time encoded in z (the grid's tf when it is not a variable).
  virtual double FinalTime(ConstVecRef /*z*/) const { return state_grid().tf(); }
  /// The grid of z's states: state_grid(), stretched to [t0, FinalTime(z)] when the final time
  /// is a variable.
  virtual TimeGrid StateGrid(ConstVecRef /*z*/) const { return state_grid(); }
  /// The states encoded in z (nx x state_grid().size()); empty for single shooting.
  virtual Mat States(ConstVecRef z) const = 0;
  /// A costate estimate from the constraint multipliers lambda (nx x state_grid().size()),
  /// in the convention H = p^T f + L; empty when the transcription has none.
  virtual Mat Costates(ConstVecRef /*z*/, ConstVecRef /*lambda*/) const { return Mat(); }

  // ---- adaptive mesh refinement (transcriptions/mesh_refinement.h) ----
  /// The local error estimate of each mesh interval at z, as TranscriptionOptions::mesh.estimate
  /// asks: the scheme's own (IntervalDefectErrors: Betts' scaled integral of the interpolant's
  /// defect; LGR: LgrIntervalErrors) or IntervalSimulationErrors; empty when the scheme has
  /// none.
  virtual Vec IntervalErrors(ConstVecRef /*z*/) const { return Vec(); }
  /// The exponent q of h with which IntervalErrors decrease at a fixed degree
  /// (DefectEstimateOrder); 0 without.
  virtual int IntervalErrorOrder() const { return 0; }
  /// The collocation points of each mesh interval when the scheme refines by degree too (LGR:
  /// ph-refinement, PhRefineMesh); empty for the fixed-order schemes (h-refinement).
  virtual std::vector<int> IntervalDegrees() const { return {}; }
  /// The states at z as a function of time on [t0, FinalTime(z)], to start a solve on another
  /// mesh from: the scheme's state interpolant where it has IntervalErrors, else piecewise
  /// linear through States(z) on StateGrid(z); empty (nu() == 0) without states.
  virtual ControlTrajectory StateTrajectory(ConstVecRef z) const;

  // ---- multiplier warm starts across meshes (transcriptions/multiplier_trajectories.h) ----
  /// The multipliers `y` of a solution z as functions of time; nullopt when the transcription
  /// has no such map, or y does not fit (NlpMultipliers::Fits) or gives no finite costates.
  virtual std::optional<MultiplierTrajectories> MultiplierTrajectoriesAt(
      ConstVecRef /*z*/, const NlpMultipliers& /*y*/) const {
    return std::nullopt;
  }
  /// Multipliers to start this NLP with at its primal starting point z0, read from another
  /// mesh's MultiplierTrajectoriesAt; empty when the transcription has no such map or the
  /// trajectories do not fit the problem.
  virtual NlpMultipliers StartingMultipliers(ConstVecRef /*z0*/,
                                             const MultiplierTrajectories& /*from*/) const {
    return NlpMultipliers();
  }
};

/// What a transcription needs besides the problem.
struct TranscriptionOptions {
  TimeGrid grid;  ///< mesh on [t0, tf] (>= 1 interval)
  TerminalMode terminal = TerminalMode::kPenalty;
  std::optional<ControlTrajectory> initial_guess;  ///< controls to start from (states by
                                                   ///< simulation); nu >= 1, covering the grid
  /// States to start from (nx components, on the horizon of initial_guess), for the schemes
  /// with state variables; default: simulated from the controls. Single shooting ignores them.
  std::optional<ControlTrajectory> initial_states;
  /// Multipliers to start from (a previous mesh's MultiplierTrajectoriesAt), read by the NLP
  /// solvers' driver (StartingMultipliers at the starting point, handed to the backend); a
  /// single Transcribe() ignores them. Set by mesh refinement with mesh.warm_multipliers.
  std::optional<MultiplierTrajectories> initial_multipliers;
  int degree = 3;  ///< LGR: collocation points per interval, 1..kMaxRadauPoints (60)
  /// LGR: collocation points of each grid interval (grid.intervals() entries, each
  /// 1..kMaxRadauPoints), as ph mesh refinement sets them; empty: `degree` on every interval.
  std::vector<int> degrees;
  NlpScaling scaling;  ///< default: none (see nlp_scaling.h)
  /// Adaptive mesh refinement (trapezoid, hermite-simpson: h; lgr: ph); default off. Read by the
  /// NLP solvers' driver (solvers/mesh_refinement_loop.h), which re-transcribes on refined grids;
  /// a single Transcribe() ignores it.
  MeshRefinementOptions mesh;
  /// Schemes whose objective is a simulation (single shooting): forward Euler (the
  /// Hamiltonian descent's discrete problem) or RK4.
  Integrator integrator = Integrator::kEuler;

  /// True when every field satisfies its rule above on its own (sizes are checked against a
  /// problem by IsValidFor) and the guesses cover the grid; otherwise false with a one-line
  /// reason in *error (may be null).
  bool IsValid(std::string* error) const;
  /// IsValid() and the options fit `ocp`: the grid spans [t0, tf] (to 1e-12 relative), the
  /// initial guess has ocp.nu() components, the initial states ocp.nx(), the scaling's sizes
  /// are nx and nu (NlpScaling::IsValidFor). For a free final time the guesses may end at their
  /// own T within the bounds (GuessFinalTime), else they must cover the grid.
  bool IsValidFor(const Ocp& ocp, std::string* error) const;
  /// Where a free final time starts: the end of initial_guess's grid when `ocp` has a free final
  /// time admitting it (a previous solution's T), else the grid's tf.
  double GuessFinalTime(const Ocp& ocp) const;

 private:
  /// IsValid without the guesses' horizon (IsValidFor checks that against the problem).
  bool IsValidOnItsOwn(std::string* error) const;
};

/// A scheme, by name ("euler", "trapezoid", "hermite-simpson", "lgr", "single-shooting").
class Transcription {
 public:
  virtual ~Transcription() = default;
  virtual std::string name() const = 0;
  /// Throws std::invalid_argument on an invalid request (for example a grid that does not span
  /// the problem's horizon).
  virtual std::unique_ptr<TranscribedNlp> Transcribe(const Ocp& ocp,
                                                     const TranscriptionOptions& options) const = 0;
};

}  // namespace ocpb
