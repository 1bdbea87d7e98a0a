// A problem of several phases, posed as one Ocp that every collocation transcription, Ipopt,
// NLopt and the judge take as it is (OCPBench problem class: core/ocp.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/ocp.h"

namespace ocpb {

/// One phase: its own problem and the bounds of its duration. The phase's Ocp brings its
/// dimensions, dynamics f_i, running cost L_i, terminal cost phi_i (at the phase's end), path
/// constraints, control set, state bounds, initial state (phase 1: fixed or bounded as it
/// declares; later phases: a guess, their start is set by the links) and its own boundary
/// constraints on (x_i(start), x_i(end)). Its terminal constraints psi_i hold at the phase's end:
/// the last phase's are the problem's terminal constraints (penalty or hard form as requested),
/// an earlier phase's are events (always hard). Its horizon [t0, tf] is only the nominal
/// duration tf - t0, where methods start.
struct PhaseSpec {
  std::shared_ptr<const Ocp> ocp;
  double min_duration = 0.0;  ///< > 0; equal to max_duration for a fixed duration
  double max_duration = 0.0;
};

/// One linkage condition between phase i and phase i + 1:
///   x_{i+1}(start)[to_state] = x_i(end)[from_state] + jump
/// (continuity with jump = 0; a stage's dropped mass as a negative jump in the mass).
struct PhaseLink {
  int from_state = 0;
  int to_state = 0;
  double jump = 0.0;
};

/// Phases 1..P joined end to start, solved as one problem on the normalized time tau in [0, 1]
/// (the classical stacking of phases: every phase runs on its own tau axis, scaled by its
/// duration):
///
///   X = (x_1, ..., x_P, T_1, ..., T_P),  U = (u_1, ..., u_P),
///   dx_i/dtau = T_i f_i(x_i, u_i),  J = sum_i [ int_0^1 T_i L_i dtau + phi_i(x_i(1)) ]
///                                       (+ phi0_i(x_i(0)) where a phase defines one),
///   path constraints, control sets and state bounds of every phase, stacked;
///   links x_{i+1}(0) = x_i(1) + jump, events psi_i(x_i(1)) = 0 (i < P) and each phase's own
///   boundary constraints as boundary constraints b(X(0), X(1)); psi_P as the terminal
///   constraints; the durations T_i static parameters in [min_duration, max_duration].
///
/// Phase i covers [t_i, t_i + T_i] of physical time with t_1 = phase 1's t0 and t_{i+1} = t_i +
/// T_i (time continuity is built in). Every derivative is exact (chain rule on the phases' own
/// derivatives; a finite-difference test checks them).
///
/// Requirements (the constructor throws std::invalid_argument naming the phase and the rule):
/// at least one phase; every phase autonomous in the sense of a free final time (f_i, L_i, c_i
/// independent of t: its times are scaled), with a fixed horizon of its own (no free final
/// time: the duration is the phase's decision here) and no static parameters of its own; 0 <
/// min_duration <= max_duration, finite; links[i] joins phase i and i + 1 (links.size() == P -
/// 1), each index inside its phase's state, no state of phase i + 1 linked twice; a later
/// phase's x0 inside its state bounds (its start takes them); the last phase's terminal weights are
/// the problem's. A phase whose dynamics do depend on t is solved with t = its nominal time, which
/// is wrong: the caller promises autonomy, as for SetFreeFinalTime.
///
/// What is shared: every phase gets the same number of intervals of the request's grid in tau
/// (one grid for all phases; refinement refines it for all of them), and the result's
/// trajectories are in tau (SplitPhases recovers each phase's own states and physical times).
class MultiPhaseOcp : public Ocp {
 public:
  MultiPhaseOcp(std::string name,
                std::vector<PhaseSpec> phases,
                std::vector<std::vector<PhaseLink>> links);

  /// Full continuity of `nx` states (x_{i+1}(0) = x_i(1)), with `jump` added where given
  /// (size nx, or empty for none).
  static std::vector<PhaseLink> Continuity(int nx, const Vec& jump = Vec());

  std::string name() const override { return name_; }

  int num_phases() const { return static_cast<int>(phases_.size()); }
  const Ocp& phase(int i) const { return *phases_.at(i).ocp; }
  /// Where phase i's states, controls and duration sit in X and U.
  int state_offset(int i) const { return state_offset_.at(i); }
  int control_offset(int i) const { return control_offset_.at(i); }
  int duration_index(int i) const { return duration_offset_ + i; }

  /// One phase of a solution, in its own variables and physical time.
  struct PhaseTrajectory {
    double start_time = 0.0;
    double duration = 0.0;
    std::vector<double> t;  ///< physical times of the state points
    Mat x;                  ///< nx_i rows, one column per state point
  };
  /// Splits stacked states (nx() rows, one column per point of `tau` in [0, 1]) into phases.
  std::vector<PhaseTrajectory> SplitPhases(const std::vector<double>& tau, const Mat& X) const;

  void Dynamics(double t, ConstVecRef x, ConstVecRef u, VecRef f) const override;
  double RunningCost(double t, ConstVecRef x, ConstVecRef u) const override;
  double TerminalCost(ConstVecRef x) const override;
  bool HasInitialCost() const override { return has_initial_cost_; }
  double InitialCost(ConstVecRef x0) const override;
  void TerminalConstraints(ConstVecRef x, VecRef psi) const override;
  void BoundaryConstraints(ConstVecRef x0, ConstVecRef xf, VecRef b) const override;
  void PathConstraints(double t, ConstVecRef x, ConstVecRef u, VecRef c) const override;

  void DynamicsJacobian(
      double t, ConstVecRef x, ConstVecRef u, VecRef f, MatRef fx, MatRef fu) const override;
  void RunningCostGradient(
      double t, ConstVecRef x, ConstVecRef u, double* L, VecRef Lx, VecRef Lu) const override;
  void TerminalCostGradient(ConstVecRef x, double* phi, VecRef phix) const override;
  void InitialCostGradient(ConstVecRef x0, double* phi0, VecRef grad) const override;
  void BoundaryConstraintsJacobian(
      ConstVecRef x0, ConstVecRef xf, VecRef b, MatRef b_x0, MatRef b_xf) const override;
  void TerminalConstraintsJacobian(ConstVecRef x, VecRef psi, MatRef psix) const override;
  void PathConstraintsJacobian(
      double t, ConstVecRef x, ConstVecRef u, VecRef c, MatRef cx, MatRef cu) const override;

  void PointHessian(double t,
                    ConstVecRef x,
                    ConstVecRef u,
                    double sigma,
                    ConstVecRef lambda,
                    ConstVecRef mu,
                    MatRef hess) const override;
  void TerminalHessian(ConstVecRef x, double sigma, ConstVecRef nu, MatRef hess) const override;
  void BoundaryHessian(ConstVecRef x0, ConstVecRef xf, ConstVecRef mu, MatRef hess) const override;
  void InitialCostHessian(ConstVecRef x0, double sigma, MatRef hess) const override;

  Vec NominalControl() const override;

 private:
  // Phase i's own time at normalized time tau (its nominal axis: phases are autonomous).
  double PhaseTime(int i, double tau) const;
  // Whether phase i's initial cost counts: its start is a decision (later phases always).
  bool CountsInitialCost(int i) const;

  std::string name_;
  std::vector<PhaseSpec> phases_;
  std::vector<std::vector<PhaseLink>> links_;
  std::vector<int> state_offset_, control_offset_, path_offset_;
  int duration_offset_ = 0;
  // Boundary rows: links first, then events (psi_i, i < P), then each phase's own rows.
  std::vector<int> event_row_, phase_boundary_row_;
  bool has_initial_cost_ = false;
};

}  // namespace ocpb
