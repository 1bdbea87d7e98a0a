// The sparse NLP shared by OCPBench's direct transcriptions (Euler, trapezoid, Hermite-Simpson,
// Legendre-Gauss-Radau): one description of variables, evaluation points and defects, and one
// implementation of values, exact sparse derivatives, bounds, starting point and costates.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "core/integrator.h"
#include "core/ocp.h"
#include "transcriptions/mesh_error.h"
#include "transcriptions/transcription.h"

namespace ocpb {

/// What a direct transcription is made of. A scheme fills one of these; CollocationNlp does the
/// rest.
///
///  - State blocks X_j (nx variables each) at times t_j, strictly increasing; block 0 is x(t0)
///    (fixed to x0 by its bounds, or within Ocp::initial_state_bounds() for a free initial
///    state) and the last block is x(tf). Blocks after the first take Ocp::state_bounds() as
///    variable bounds.
///  - Control blocks U_i (nu variables each) at times s_i.
///  - Points e = (t_e, X_{state(e)}, U_{control(e)}) where f, L and c are evaluated.
///  - Defects d, nx rows each, for one interval k(d):
///        sum_j a_dj X_j - sum_e b_de f(t_e, X_{state(e)}, U_{control(e)}) = 0
///    (b carries the step length).
///  - Objective  sum_e w_e L(t_e, X_{state(e)}, U_{control(e)}) + Phi(X_last) [+ phi0(X_0)],
///    Phi = phi (+ the terminal penalty sum_i w_i psi_i^2 in TerminalMode::kPenalty), phi0 the
///    initial cost of a free initial state.
///  - Path constraints c(t_e, X_{state(e)}, U_{control(e)}) <= 0 at the points marked `path`;
///    ball blocks of U as |U_i,b - center|^2 <= radius^2 for every control block; box blocks of U
///    as variable bounds; psi(X_last) = 0 in TerminalMode::kHard; boundary constraints
///    b_lo <= b(X_0, X_last) <= b_hi in both modes.
struct CollocationLayout {
  struct Term {
    int index = 0;
    double coeff = 0.0;
  };
  struct StateBlock {
    double t = 0.0;
    int offset = 0;
    /// k when this block is x(t_k), the first state of interval k (N for x(tf)); -1 for a block
    /// inside an interval. Its costate is then the gradient with respect to X_j of the part of
    /// the Lagrangian that belongs to intervals >= k (and the terminal terms; path constraints at
    /// t_k count there too): the sensitivity of the cost-to-go, which at a KKT point equals minus
    /// the rest by stationarity. For x(t0) it is the multiplier of the fixing bounds.
    int interval_start = -1;
    /// Blocks inside an interval: costate = costate_scale * (multiplier of defect costate_defect)
    /// + sum over costate_blocks (j, c) of c * (costate of interval-start block j).
    int costate_defect = -1;
    double costate_scale = 0.0;
    std::vector<Term> costate_blocks;
  };
  struct ControlBlock {
    double t = 0.0;
    int offset = 0;
  };
  struct Point {
    double t = 0.0;
    int state = 0;
    int control = 0;
    double cost_weight = 0.0;  ///< w_e
    /// The part of w_e that belongs to the interval starting at this point's state block (for
    /// the costate rule above; 0 when the block is not an interval start).
    double future_cost_weight = 0.0;
    bool path = false;
  };
  struct Defect {
    int interval = 0;
    std::vector<Term> states;    ///< (state block j, a_dj)
    std::vector<Term> dynamics;  ///< (point e, b_de)
  };

  int nx = 0, nu = 0;
  int num_variables = 0;
  std::vector<StateBlock> states;
  std::vector<ControlBlock> controls;
  std::vector<Point> points;
  std::vector<Defect> defects;

  /// Appends a state (control) block at the next free offset; returns its index.
  int AddState(double t, int interval_start = -1);
  int AddControl(double t);
};

/// A TranscribedNlp built from a CollocationLayout; subclasses only say how control blocks
/// become a ControlTrajectory.
///
/// Constraint rows, in this order: all defects (nx rows each, in layout order), path constraints
/// (nc rows per path point, in point order), ball constraints (one row per control block and
/// ball block), terminal constraints psi (hard mode only), boundary constraints b
/// (Ocp::num_boundary() rows).
///
/// Derivatives are exact: the constraint Jacobian from Ocp::DynamicsJacobian and
/// PathConstraintsJacobian; the Hessian of sigma f + lambda^T g as the sum over points of
/// Ocp::PointHessian(t_e, x_e, u_e, sigma w_e, -sum_d b_de lambda_d, mu_e), plus TerminalHessian
/// (with the penalty's Gauss-Newton term 2 psi_x^T W psi_x + 2 sum w_i psi_i psi_i,xx), 2 mu I
/// for the balls, Ocp::BoundaryHessian over (X_0, X_last) and sigma InitialCostHessian at X_0. Both
/// sparsity patterns are built once, in the constructor, from dense (x, u)-blocks, and hold unique
/// (row, col) entries (no repeated triplets); the Hessian pattern is the lower triangle (row >=
/// col).
///
/// Multipliers follow the convention of HessianValues: at a KKT point sigma grad f + J^T lambda
/// (plus bound multipliers) vanishes, as in Ipopt. Costates() turns them into p with
/// H = p^T f + L.
///
/// Free final time (Ocp::free_final_time()): T is one more variable, the last, with the problem's
/// bounds and the grid's tf as its start. The layout is built on the nominal horizon [t0, tf];
/// at T every step length scales by r = (T - t0) / (tf - t0), so every dynamics coefficient b_de
/// and cost weight w_e is multiplied by r (the schemes' state coefficients a_dj do not carry h)
/// and the problem, autonomous by Ocp's contract, is evaluated at the nominal times. Hence
///   d(defect d)/dT = -(1 / (tf - t0)) sum_e b_de f_e,   dJ/dT = (1 / (tf - t0)) sum_e w_e L_e,
/// and the Hessian gains the cross terms d^2/dT d(x_e, u_e) = (1 / (tf - t0)) grad_(x,u) (sigma
/// w_e L_e - sum_d b_de lambda_d^T f_e) (d^2/dT^2 = 0: the Lagrangian is affine in r). Controls(),
/// StateGrid() and Costates() live on the stretched axis [t0, T].
///
/// The Ocp must outlive this object. Evaluations return false when a value is not finite.
class CollocationNlp : public TranscribedNlp {
 public:
  CollocationNlp(const Ocp& ocp,
                 const TranscriptionOptions& options,
                 CollocationLayout layout,
                 Integrator start_integrator);

  // ---- Nlp ----
  int num_variables() const override { return layout_.num_variables + (free_time_ ? 1 : 0); }
  int num_constraints() const override { return num_constraints_; }
  void Bounds(Vec* z_lower, Vec* z_upper, Vec* g_lower, Vec* g_upper) const override;
  /// Controls from TranscriptionOptions::initial_guess (default: Ocp::NominalControl() projected
  /// onto U) at every control block's time (the left limit at tf, the right limit elsewhere),
  /// projected onto U; states from TranscriptionOptions::initial_states at every state point,
  /// or else by simulating the resulting ControlTrajectory from x0 on state_grid() with the
  /// scheme's start integrator (Euler for the Euler transcription, so its start is feasible;
  /// RK4 otherwise). If the states are not finite, every state block is set to x0. A free final
  /// time starts at TranscriptionOptions::GuessFinalTime (a previous solution's T), the guesses
  /// read at the stretched times of the nominal layout.
  Vec StartingPoint() const override;
  bool Objective(ConstVecRef z, double* f) const override;
  bool Gradient(ConstVecRef z, VecRef grad) const override;
  bool Constraints(ConstVecRef z, VecRef g) const override;
  bool JacobianValues(ConstVecRef z, VecRef values) const override;
  bool HasHessian() const override { return true; }
  bool HessianValues(ConstVecRef z, double sigma, ConstVecRef lambda, VecRef values) const override;

  // ---- TranscribedNlp ----
  ControlTrajectory Controls(ConstVecRef z) const override;
  const TimeGrid& state_grid() const override { return state_grid_; }
  bool HasFinalTimeVariable() const override { return free_time_; }
  double FinalTime(ConstVecRef zhat) const override;
  TimeGrid StateGrid(ConstVecRef zhat) const override;
  Mat States(ConstVecRef z) const override;
  /// p (nx x state_grid().size()) from the NLP's multipliers `lambda` at z (as a solver returns
  /// them, scaled NLP); empty when lambda.size() != num_constraints(). Variable-bound
  /// multipliers are not in it: where Ocp::state_bounds() are active, p differs from the
  /// path-row form's by the bound multiplier (a known limit).
  Mat Costates(ConstVecRef z, ConstVecRef lambda) const override;
  /// With TranscriptionOptions::mesh.estimate == kSimulation IntervalSimulationErrors on the
  /// mesh (stretched to T for a free final time) with every state block and Controls(z), else
  /// SchemeIntervalErrors(z).
  Vec IntervalErrors(ConstVecRef z) const override;
  int IntervalErrorOrder() const override;
  ControlTrajectory StateTrajectory(ConstVecRef z) const override;
  /// Costates(z, y.lambda) on the state points, interpolated per mesh interval; path, ball and
  /// control-bound multipliers divided by their point's weight r w_e (r: the final-time ratio);
  /// terminal and final-time multipliers as they are (MultiplierTrajectories). Physical units.
  std::optional<MultiplierTrajectories> MultiplierTrajectoriesAt(
      ConstVecRef z, const NlpMultipliers& y) const override;
  /// The inverse of MultiplierTrajectoriesAt on this layout, at the starting point z0 (times
  /// stretched by its final-time ratio): p read at every state point, path, ball and
  /// control-bound multipliers r w_e times the densities at their points, terminal and
  /// final-time multipliers carried; then the defect multipliers that make Costates(z0, lambda)
  /// equal those p: for a point inside an interval its costate_defect's multiplier from
  /// (p_j - sum_c c p_c) / costate_scale, then per interval the one remaining defect from its
  /// start block's costate relation (an nx x nx solve at z0). Exact (to rounding) on the
  /// mesh the trajectories came from at their own z. Empty when an interval has other than one
  /// defect without an interior block, a solve is singular, or the trajectories' sizes do not
  /// fit.
  NlpMultipliers StartingMultipliers(ConstVecRef z0,
                                     const MultiplierTrajectories& from) const override;

  // ---- for tests and tools ----
  const CollocationLayout& layout() const { return layout_; }
  const Ocp& ocp() const { return ocp_; }
  TerminalMode terminal_mode() const { return mode_; }
  /// Control block values (nu x controls), physical units.
  Mat ControlValues(ConstVecRef z) const;
  /// First row of each constraint group.
  int defect_row(int d) const { return d * layout_.nx; }
  int path_row_begin() const { return path_row_begin_; }
  int ball_row_begin() const { return ball_row_begin_; }
  int terminal_row_begin() const { return terminal_row_begin_; }
  int boundary_row_begin() const { return boundary_row_begin_; }
  /// Physical variables z = D zhat from the NLP's (scaled) variables, and back.
  Vec Unscale(ConstVecRef zhat) const { return zhat.cwiseProduct(var_scale_); }
  Vec Scale(ConstVecRef z) const { return z.cwiseQuotient(var_scale_); }

 protected:
  /// The scheme's interpolation of the control block values (nu x controls, physical) on `grid`:
  /// the transcription's mesh, or (free final time) that mesh stretched to [t0, T]. The schemes
  /// interpolate in each interval's own coordinate (t - t_k) / h_k, so the stretched controls are
  /// exactly the nominal ones on the stretched time axis, interval by interval.
  virtual ControlTrajectory MakeControls(const Mat& values, const TimeGrid& grid) const = 0;
  /// The state interpolant of the scheme between mesh nodes, for the mesh error estimate;
  /// nullopt (default): no estimate.
  virtual std::optional<CollocationInterpolant> mesh_interpolant() const { return std::nullopt; }
  /// The scheme's own estimate (MeshErrorEstimate::kScheme): IntervalDefectErrors with the node
  /// states (the interval-start blocks) and Controls(z); empty without mesh_interpolant().
  virtual Vec SchemeIntervalErrors(ConstVecRef zhat) const;
  const TimeGrid& grid() const { return grid_; }
  // The mesh on the solution's horizon (stretched to T for a free final time).
  TimeGrid SolutionMesh(ConstVecRef zhat) const;

 private:
  struct PointUse {  // point e appears in defect d with coefficient -b
    int defect;
    double coeff;
    int x_slots;  // base into jac_slots_ of the nx x nx block (row-major)
    int u_slots;  // base of the nx x nu block
  };
  struct StateUse {  // X_j appears in defect d with coefficient a: diagonal entries
    int defect;
    int state;
    double coeff;
    int x_slots;
  };

  void BuildStructure();
  // The node states x(t_k) (nx x N+1) at z.
  Mat NodeStates(ConstVecRef zhat) const;
  // r = (T - t0) / (tf - t0) at physical z (1 without a free final time).
  double Ratio(const Vec& z) const;
  // Physical evaluations (z physical, lambda physical).
  bool EvalObjective(const Vec& z, double* f) const;
  bool EvalGradient(const Vec& z, Vec* grad) const;
  bool EvalConstraints(const Vec& z, Vec* g) const;
  bool EvalJacobian(const Vec& z, Vec* values) const;
  // Adds the defect rows' entries (states and dynamics, the T column) to the Jacobian values.
  void AddDefectJacobian(const Vec& z, Vec* values) const;
  // Adds the other rows' entries (path constraints, balls, hard terminal constraints), each
  // times scale[slot] when `scale` is not null; false when one is not finite.
  bool AddOtherJacobianRows(const Vec& z, const double* scale, double* values) const;
  bool EvalHessian(const Vec& z, double sigma, const Vec& lambda, Vec* values) const;

  const Ocp& ocp_;
  TimeGrid grid_;
  TerminalMode mode_;
  MeshErrorEstimate mesh_estimate_;
  std::optional<ControlTrajectory> initial_guess_;
  std::optional<ControlTrajectory> initial_states_;
  double start_final_time_;  // T of the starting point (TranscriptionOptions::GuessFinalTime)
  CollocationLayout layout_;
  Integrator start_integrator_;
  TimeGrid state_grid_;
  int nx_, nu_, nc_, npsi_, nb_;
  bool free_time_ = false;
  bool initial_cost_ = false;  // a free initial state with phi0: its terms at block 0
  int time_index_ = -1;        // the variable T (free final time), after the layout's variables
  double inv_duration_ = 1.0;  // 1 / (tf - t0) of the nominal horizon
  std::vector<int> time_jac_slots_;   // per defect: base of its nx slots in the T column
  std::vector<int> time_hess_slots_;  // per point: base of its nx + nu slots in the T row
  int num_constraints_ = 0;
  int path_row_begin_ = 0, ball_row_begin_ = 0, terminal_row_begin_ = 0;
  int boundary_row_begin_ = 0;
  std::vector<int> path_point_row_;  // per point: first path row, or -1
  std::vector<int> ball_blocks_;     // indices into control_set().blocks() of the ball blocks

  // Scaling: z = var_scale .* zhat, ghat = row_scale .* g, fhat = objective_scale * f.
  double objective_scale_ = 1.0;
  Vec var_scale_, row_scale_;
  Vec jac_value_scale_, hess_value_scale_;

  // Jacobian structure.
  std::vector<int> jac_slots_;
  // The defect rows' Jacobian values times jac_value_scale_ when they do not depend on z
  // (Ocp::HasAffineDynamics on a fixed horizon), else empty.
  Vec scaled_defect_jacobian_;
  std::vector<std::vector<PointUse>> point_uses_;  // per point
  std::vector<StateUse> state_uses_;
  std::vector<int> path_x_slots_, path_u_slots_;         // per point (base into jac_slots_), or -1
  std::vector<int> ball_slots_;                          // per ball row: base of its `size` slots
  int terminal_slots_ = -1;                              // npsi x nx
  int boundary_x0_slots_ = -1, boundary_xf_slots_ = -1;  // nb x nx each
  // Hessian structure.
  std::vector<int> hess_slots_;
  std::vector<int> point_hess_slots_;  // per point: base of (nx+nu)^2 entries (-1: upper)
  struct HessPair {
    int entry;  // index into the column-major (nx+nu)^2 point Hessian
    int slot;   // index into the Hessian values
  };
  std::vector<HessPair> point_hess_pairs_;   // per point, its lower-triangle entries in order
  std::vector<int> point_hess_pairs_begin_;  // per point: first pair; one more at the end
  int terminal_hess_slots_ = -1;             // nx x nx
  int initial_hess_slots_ = -1;              // nx x nx at x(t0), with initial_cost_
  int boundary_hess_slots_ = -1;             // (2 nx)^2 over (x(t0), x(tf)), lower triangle
  std::vector<int> ball_hess_slots_;         // per ball row: base of `size` diagonal slots
};

/// Throws std::invalid_argument unless `options` is a valid request for `ocp`: the grid spans
/// [t0, tf] (to 1e-12 relative), the initial guess has nu components, the scaling is valid for
/// (nx, nu), and static parameters have zero dynamics (Ocp::CheckStaticParameterDynamics).
void ValidateTranscriptionOptions(const Ocp& ocp, const TranscriptionOptions& options);

}  // namespace ocpb
