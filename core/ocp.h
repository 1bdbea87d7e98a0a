// The optimal-control problem every method of OCPBench consumes.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "core/control_set.h"
#include "core/control_trajectory.h"
#include "core/time_grid.h"
#include "core/types.h"

namespace ocpb {

/// How a method treats the terminal constraints psi(x(tf)) = 0.
enum class TerminalMode {
  kPenalty,  ///< add sum_i w_i psi_i(x(tf))^2 to the cost (the paper's form)
  kHard,     ///< enforce psi(x(tf)) = 0 as constraints
};
const char* ToString(TerminalMode mode);

/// A free final time: tf is a decision variable in [lower, upper] (Ocp::free_final_time()).
struct FreeFinalTime {
  double lower = 0.0;
  double upper = 0.0;
};

/// Componentwise bounds lower <= v <= upper; an entry may be -inf (lower) or +inf (upper).
struct VectorBounds {
  Vec lower;
  Vec upper;
  /// max_i max(lower_i - v_i, v_i - upper_i, 0): 0 inside, the distance outside.
  double Violation(ConstVecRef v) const;
};

/// What a method that needs a reformulated problem (the Hamiltonian descent) may ask of
/// Ocp::HamiltonianReformulation. An unset field means "the problem's own default", which the
/// problem's header states.
struct HamiltonianReformulationOptions {
  /// rho > 0 in the path-constraint penalty rho * sum_i max(0, c_i(t, x, u))^2 added to L.
  std::optional<double> path_penalty;
  /// eps > 0 in the control regularization eps |u|^2 added to L where H is linear in u
  /// (bang-bang or singular arcs).
  std::optional<double> regularization;
};

/// An optimal-control problem in Bolza form on a fixed horizon [t0, tf]:
///
///   minimize    J = int_{t0}^{tf} L(t, x, u) dt + phi(x(tf)) [+ sum_i w_i psi_i(x(tf))^2]
///   subject to  x' = f(t, x, u),  x(t0) = x0,
///               u(t) in U                       (a ControlSet),
///               c(t, x, u) <= 0                 (path constraints),
///               psi(x(tf)) = 0                  (hard form only).
///
/// Four widenings, each off by default (a problem that sets none is the problem above, solved
/// exactly as before):
///  - state bounds x_lo <= x(t) <= x_hi on (t0, tf] (SetStateBounds): the collocation
///    transcriptions make them bounds of their state variables (not constraint rows), at every
///    state point but the initial one; the judge checks them on its fine re-simulation;
///  - a free or partly free initial state (SetInitialStateBounds): x(t0) in [l0, u0] is then a
///    decision, x0() only where methods start, and the cost may add phi0(x(t0))
///    (InitialCost): J = phi0(x(t0)) + int L + phi(x(tf)). The initial node takes the
///    initial-state bounds alone (a problem whose state bounds hold at t0 too repeats them
///    there). A result carries the x(t0) it chose (SolveResult::initial_state).
///  - static parameters (SetStaticParameters): the last np components of x are constant
///    decisions p in [p_lo, p_hi] (their dynamics are 0), read by f, L, phi, c, psi and b like
///    any state, so every derivative with respect to p is exact; transcribed as a partly free
///    initial state whose free part stays constant (np variables per state point);
///  - boundary constraints b_lo <= b(x(t0), x(tf)) <= b_hi (SetBoundaryConstraints and
///    BoundaryConstraints; equalities where b_lo = b_hi), coupling both ends (a periodic state,
///    a total change, an initial condition given implicitly). Always hard constraints, in both
///    terminal forms (the penalty form is psi's alone).
/// Methods that do not take them (single shooting, hamiltonian and the Hamiltonian family,
/// indirect-newton, riccati-ip, baseline) report SolveStatus::kNotApplicable with the reason.
/// The collocation NLPs' costate estimates (Costates) use the constraint multipliers only: with
/// state bounds active the bound multipliers are not in them (the path-row form of the same
/// bound puts them in), and mesh refinement's multiplier warm start carries neither those nor
/// the boundary constraints' multipliers (it starts them at 0).
///
/// Free final time (Ocp::free_final_time(), off by default): tf is then minimized over too, in
/// [lower, upper], and tf() is only its nominal value, where methods start (a request's grid
/// spans [t0, tf()]; a result's state_grid spans [t0, its tf]). Such a problem is autonomous:
/// f, L and c do not depend on t (SetFreeFinalTime's contract), and phi depends on x(tf) alone,
/// so the optimality condition is H(tf) = 0. Minimum time is L = 1.
///
/// The penalized cost J and the unpenalized cost Jbar = int L + phi come from the same
/// definition; `terminal_weights()` holds the w_i. The Hamiltonian is H = p^T f + L.
///
/// Derivatives: every first and second derivative below is exact (forward-mode AD in
/// AutoDiffOcp, or hand-written by a problem and then tested against finite differences).
/// Outputs are written into caller-owned storage of the right size; inputs are not resized.
/// The interface is const and keeps no mutable state, so one problem may be shared by threads.
class Ocp {
 public:
  virtual ~Ocp() = default;

  /// Registry name of the problem (for example "double-integrator").
  virtual std::string name() const = 0;

  int nx() const { return nx_; }
  int nu() const { return nu_; }
  int num_terminal() const { return npsi_; }
  int num_path() const { return nc_; }
  double t0() const { return t0_; }
  double tf() const { return tf_; }
  const Vec& x0() const { return x0_; }
  /// The penalty weights w_i of the terminal constraints (TerminalMode::kPenalty). Default: 1
  /// for every i, set by SetDimensions; see terminal_weights_chosen().
  const Vec& terminal_weights() const { return terminal_weights_; }
  /// True once the problem called SetTerminalWeights (or has no terminal constraints). The
  /// default w = 1 is rarely right (with psi = 0 weighed 1 against the cost, a double integrator
  /// misses its target by 0.75): results judged in the penalty form of a problem whose weights
  /// were never chosen carry a warning (JudgeResult, solvers/judge.h). A problem that means
  /// w = 1 says so with SetTerminalWeights(Vec::Ones(npsi)).
  bool terminal_weights_chosen() const { return npsi_ == 0 || terminal_weights_chosen_; }
  const ControlSet& control_set() const { return control_set_; }
  /// Set when the final time is free (see the class comment); empty for a fixed horizon.
  const std::optional<FreeFinalTime>& free_final_time() const { return free_final_time_; }
  /// State bounds x_lo <= x(t) <= x_hi on (t0, tf] (SetStateBounds); empty when there are none.
  const std::optional<VectorBounds>& state_bounds() const { return state_bounds_; }
  /// Bounds on x(t0) when the initial state is free or partly free (SetInitialStateBounds);
  /// empty when x(t0) = x0() is fixed.
  const std::optional<VectorBounds>& initial_state_bounds() const { return initial_state_bounds_; }
  /// True when some component of x(t0) is a decision: initial-state bounds with lower < upper
  /// somewhere (bounds that fix every component leave x(t0) = x0 fixed).
  bool HasFreeInitialState() const { return free_initial_state_; }
  /// The bounds x(t0) takes in a transcription: initial_state_bounds(), or [x0, x0] when fixed.
  VectorBounds InitialNodeBounds() const;
  /// The number of static parameters: the last num_static_parameters() components of x
  /// (SetStaticParameters; default 0).
  int num_static_parameters() const { return np_; }
  /// Throws std::invalid_argument (one line, naming the problem and the component) unless the
  /// dynamics of every static parameter and their derivatives in x and u are 0 at (t0, x0, the
  /// nominal control projected on U): a problem that forgot to zero them would let its
  /// "parameters" drift. (One point: a dynamics that vanishes only there is not caught.)
  void CheckStaticParameterDynamics() const;
  /// The number of boundary constraints b(x(t0), x(tf)) (SetBoundaryConstraints; default 0).
  int num_boundary() const { return nb_; }
  /// Their bounds b_lo <= b <= b_hi (size num_boundary() each).
  const VectorBounds& boundary_bounds() const { return boundary_bounds_; }
  /// max_i of how far b_i(x0, xf) lies outside [b_lo,i, b_hi,i] (0 inside, and without any).
  double BoundaryViolation(ConstVecRef x0, ConstVecRef xf) const;
  /// Whether a trajectory may end at `tf`: tf == tf() to 1e-9 relative for a fixed horizon,
  /// tf in [lower, upper] (to the same tolerance) for a free final time.
  bool AdmitsFinalTime(double tf) const;
  /// Which end a grid may have (GridOnHorizon): kNominal, the problem's own tf() (what a
  /// request's grid spans, for a free final time too); kAdmissible, any final time
  /// AdmitsFinalTime accepts (a free-time solution's [t0, T]).
  enum class HorizonEnd { kNominal, kAdmissible };
  /// The one check, for every method and the evaluator, that `grid` lies on the problem's
  /// horizon: at least two points, grid.t0() == t0() and its end as `end` says, to
  /// AdmitsFinalTime's tolerance (1e-9 relative to max(1, |t0|, |tf|)).
  bool GridOnHorizon(const TimeGrid& grid, HorizonEnd end) const;
  /// Empty when GridOnHorizon, else the one-line reason: "the grid [a, b] does not span the
  /// horizon [t0, tf] of problem 'NAME'" (a free final time's bounds named with kAdmissible).
  std::string GridOffHorizon(const TimeGrid& grid, HorizonEnd end) const;

  // ---- values ------------------------------------------------------------------
  virtual void Dynamics(double t, ConstVecRef x, ConstVecRef u, VecRef f) const = 0;
  virtual double RunningCost(double t, ConstVecRef x, ConstVecRef u) const = 0;
  /// phi(x(tf)), without the terminal penalty.
  virtual double TerminalCost(ConstVecRef x) const = 0;
  /// True when the problem defines an initial cost phi0 (default false: phi0 = 0). It counts
  /// (in the transcriptions and the judge) only when the initial state is free: for a fixed
  /// x(t0) it would be a constant, and no method adds it.
  virtual bool HasInitialCost() const { return false; }
  /// phi0(x(t0)); default 0.
  virtual double InitialCost(ConstVecRef /*x0*/) const { return 0.0; }
  /// psi(x(tf)) (size num_terminal()).
  virtual void TerminalConstraints(ConstVecRef x, VecRef psi) const = 0;
  /// b(x(t0), x(tf)) (size num_boundary()). The default, for num_boundary() == 0, writes
  /// nothing; a problem that declares boundary constraints must override it and the two below
  /// (AutoDiffOcp does, from EvalBoundaryConstraints).
  virtual void BoundaryConstraints(ConstVecRef x0, ConstVecRef xf, VecRef b) const;
  /// c(t, x, u) <= 0 (size num_path()).
  virtual void PathConstraints(double t, ConstVecRef x, ConstVecRef u, VecRef c) const = 0;

  // ---- first derivatives ---------------------------------------------------------
  /// f, f_x (nx x nx) and f_u (nx x nu).
  virtual void DynamicsJacobian(
      double t, ConstVecRef x, ConstVecRef u, VecRef f, MatRef fx, MatRef fu) const = 0;
  /// L, L_x and L_u.
  virtual void RunningCostGradient(
      double t, ConstVecRef x, ConstVecRef u, double* L, VecRef Lx, VecRef Lu) const = 0;
  virtual void TerminalCostGradient(ConstVecRef x, double* phi, VecRef phix) const = 0;
  /// phi0 and its gradient (default: 0 and zeros).
  virtual void InitialCostGradient(ConstVecRef x0, double* phi0, VecRef grad) const;
  /// b, b_x0 = db/dx(t0) and b_xf = db/dx(tf) (nb x nx each).
  virtual void BoundaryConstraintsJacobian(
      ConstVecRef x0, ConstVecRef xf, VecRef b, MatRef b_x0, MatRef b_xf) const;
  /// psi and psi_x (npsi x nx).
  virtual void TerminalConstraintsJacobian(ConstVecRef x, VecRef psi, MatRef psix) const = 0;
  /// c, c_x (nc x nx), c_u (nc x nu).
  virtual void PathConstraintsJacobian(
      double t, ConstVecRef x, ConstVecRef u, VecRef c, MatRef cx, MatRef cu) const = 0;

  // ---- second derivatives -------------------------------------------------------
  /// The Hessian with respect to z = (x, u) ((nx+nu) x (nx+nu), full and symmetric) of
  ///   sigma L(t, x, u) + lambda^T f(t, x, u) + mu^T c(t, x, u).
  virtual void PointHessian(double t,
                            ConstVecRef x,
                            ConstVecRef u,
                            double sigma,
                            ConstVecRef lambda,
                            ConstVecRef mu,
                            MatRef hess) const = 0;
  /// The Hessian with respect to x (nx x nx) of sigma phi(x) + nu^T psi(x).
  virtual void TerminalHessian(ConstVecRef x, double sigma, ConstVecRef nu, MatRef hess) const = 0;
  /// The Hessian with respect to (x(t0), x(tf)) (2nx x 2nx, full and symmetric) of mu^T b.
  virtual void BoundaryHessian(ConstVecRef x0, ConstVecRef xf, ConstVecRef mu, MatRef hess) const;
  /// The Hessian (nx x nx) of sigma phi0(x0) (default: zeros).
  virtual void InitialCostHessian(ConstVecRef x0, double sigma, MatRef hess) const;

  // ---- pointwise Hamiltonian minimizer -------------------------------------------
  /// True when MinimizeHamiltonian is available in closed form.
  virtual bool HasHamiltonianMinimizer() const { return false; }
  /// u* = argmin_{u in U} H(t, x, u, p) = p^T f(t, x, u) + L(t, x, u).
  /// Only called when HasHamiltonianMinimizer(); the default throws std::logic_error.
  virtual void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const;
  /// The pointwise work of one descent direction: u* = MinimizeHamiltonian(t, x, p) written to
  /// u_star, and the Hamiltonian at u* and at u, *h_star = H(t, x, u*, p) and
  /// *h_now = H(t, x, u, p). `f` is caller-owned scratch of size nx(). The default computes them
  /// from MinimizeHamiltonian, Dynamics and RunningCost; a problem whose L shares expensive work
  /// between the two controls (comm-path2d evaluates its channel at x once, not three times)
  /// overrides it, and must return the default's numbers to rounding (its tests check this).
  virtual void MinimizeAndCompareHamiltonian(double t,
                                             ConstVecRef x,
                                             ConstVecRef p,
                                             ConstVecRef u,
                                             VecRef u_star,
                                             double* h_star,
                                             double* h_now,
                                             VecRef f) const;
  /// The indirect method's work at one node: u* = MinimizeHamiltonian(t, x, p) written to u,
  /// then DynamicsJacobian (f, f_x, f_u) and RunningCostGradient (L, L_x, L_u) at (t, x, u*).
  /// The default makes those three calls; a problem whose calls share expensive work
  /// (comm-path2d evaluates its channel at x once, not twice) overrides it, and must return the
  /// default's numbers bitwise (its tests check this): Newton's iterates must not depend on it.
  /// Not forwarded by wrappers (ForwardingOcp): a wrapper that changes one of the three gets the
  /// default, which composes its own versions.
  virtual void MinimizeHamiltonianWithGradients(double t,
                                                ConstVecRef x,
                                                ConstVecRef p,
                                                VecRef u,
                                                VecRef f,
                                                MatRef fx,
                                                MatRef fu,
                                                double* L,
                                                VecRef Lx,
                                                VecRef Lu) const;
  /// A number m with L(t, x, u) >= m for every t, every x and every u in U, when the problem
  /// knows one (default: none). The Hamiltonian descent uses it to reject Armijo trials from a
  /// states-only simulation, J >= m (tf - t0) + Phi(x(tf)), without changing its iterates.
  virtual std::optional<double> RunningCostLowerBound() const { return std::nullopt; }
  /// True when the problem asserts that f(t, x, u) = A(t) x + B(t) u + c(t), affine in x and u
  /// jointly (default false). Then the forward-Euler final state is an affine function of the
  /// control samples, and the Hamiltonian descent's Armijo prefilter gets x_N(U + s d) for
  /// every trial step s from one extra states-only simulation per iteration instead of one per
  /// trial (the iterates do not change; tests check both the claim and the iterates).
  virtual bool HasAffineDynamics() const { return false; }
  /// The control every method starts from when the request gives no initial guess, constant in
  /// time and projected onto U by the method (default: u = 0). A problem overrides it when u = 0
  /// is a poor start (the minimum-time problems: w = 0 does not steer).
  virtual Vec NominalControl() const { return Vec::Zero(nu_); }
  /// NominalControl(), checked: every method starts from this. Throws std::invalid_argument
  /// naming the problem when it does not return nu finite values.
  Vec CheckedNominalControl() const;
  /// Optional: the plan a user would run without optimizing anything, on `grid` (the comm
  /// problems: the straight segment S-D, or the given path, at constant speed with the shortest
  /// speed-up and braking |u| <= umax allows, and a constant rate that sends c bits by tf). The
  /// "baseline" method returns it, so it is judged like any method's answer. The default (and a
  /// problem whose parameters admit no such plan) returns nullopt with the reason in *why_not.
  virtual std::optional<ControlTrajectory> BaselinePlan(const TimeGrid& grid,
                                                        std::string* why_not) const;

  // ---- reformulation for the Hamiltonian method ------------------------------------
  /// The problem the Hamiltonian method should solve in place of this one, or nullptr (the
  /// default) when it solves this one as it is. A problem overrides this when it does not fit
  /// the method as stated but a documented reformulation does:
  ///  - path constraints c <= 0 become the penalty rho * sum_i max(0, c_i)^2 in L (the result has
  ///    num_path() == 0 and a MinimizeHamiltonian that is exact for the penalized H);
  ///  - H linear in u (singular arcs) gets eps |u|^2 added to L (and the exact clipped minimizer).
  /// The result keeps nx, nu, the horizon, x0, U and the terminal part; it owns everything it
  /// needs (it may outlive this object). Its optimum differs from this problem's by the
  /// reformulation's error, which the problem's header quantifies; a method should judge its
  /// controls on this problem (the common evaluator does). Throws std::invalid_argument when an
  /// option is out of range (rho <= 0, eps <= 0, non-finite).
  virtual std::unique_ptr<Ocp> HamiltonianReformulation(
      const HamiltonianReformulationOptions& /*options*/) const {
    return nullptr;
  }

  // ---- conveniences built on the above -------------------------------------------
  /// The terminal penalty sum_i w_i psi_i(x)^2.
  double TerminalPenalty(ConstVecRef x) const;
  /// phi(x) + TerminalPenalty(x) in penalty mode, phi(x) in hard mode.
  double TerminalObjective(ConstVecRef x, TerminalMode mode) const;
  /// The gradient of TerminalObjective.
  void TerminalObjectiveGradient(ConstVecRef x,
                                 TerminalMode mode,
                                 double* value,
                                 VecRef grad) const;
  /// H(t, x, u, p) = p^T f + L.
  double Hamiltonian(double t, ConstVecRef x, ConstVecRef u, ConstVecRef p) const;

 protected:
  /// Problems call these from their constructor; they validate sizes and values and throw
  /// std::invalid_argument with a one-line message on bad input.
  ///
  /// The dimensions. Defaults it sets for what a problem does not set afterwards: x0 = 0,
  /// terminal weights w = 1 (not chosen: see terminal_weights_chosen()), U = R^nu (unbounded).
  /// Problems derived from AutoDiffOcp get their dimensions from its template arguments and
  /// need not call it (AutoDiffOcp's SetDimensions only checks agreement).
  void SetDimensions(int nx, int nu, int npsi, int nc);
  /// The horizon [t0, tf]; default [0, 1] (every problem should set its own).
  void SetHorizon(double t0, double tf);
  /// x(t0) (size nx, finite); default 0.
  void SetInitialState(const Vec& x0);
  /// The penalty weights w_i > 0 of psi_i (size npsi); marks them chosen.
  void SetTerminalWeights(const Vec& w);
  /// U (dimension nu); default unbounded.
  void SetControlSet(const ControlSet& set);
  /// Declares the final time free in [lower, upper]; call after SetHorizon. Needs finite
  /// t0 < lower <= tf() <= upper. The caller promises an autonomous problem (f, L, c
  /// independent of t); its tests should check it.
  void SetFreeFinalTime(double lower, double upper);
  /// State bounds x_lo <= x(t) <= x_hi on (t0, tf] (size nx each; -inf / +inf for an
  /// unbounded side; lower <= upper, no NaN). Replaces a path row c = x - x_hi <= 0: the NLP
  /// solvers see them as variable bounds.
  void SetStateBounds(const Vec& lower, const Vec& upper);
  /// Makes x(t0) a decision in [lower, upper] (size nx each; lower <= upper, no NaN; a
  /// component with lower == upper stays fixed). x0() (SetInitialState, call it first) is where
  /// methods start and must lie inside.
  void SetInitialStateBounds(const Vec& lower, const Vec& upper);
  /// Declares num_boundary() = lower.size() boundary constraints lower <= b(x(t0), x(tf)) <=
  /// upper (same sizes, no NaN, lower <= upper, -inf / +inf for a one-sided one, lower == upper
  /// for an equality). The problem defines b by overriding BoundaryConstraints and its
  /// derivatives (AutoDiffOcp: EvalBoundaryConstraints).
  void SetBoundaryConstraints(const Vec& lower, const Vec& upper);
  /// Declares the last np = lower.size() components of x static parameters: decisions in
  /// [lower, upper], constant in time, starting at `guess` (sizes np, 1 <= np <= nx, no NaN,
  /// lower <= guess <= upper). The problem's dynamics must return 0 for them (the
  /// transcriptions check it before solving). Call after SetInitialState and
  /// SetInitialStateBounds: it sets x0's last np entries to `guess` and the initial-state
  /// bounds of those components to [lower, upper] (the others keep theirs, fixed when none).
  void SetStaticParameters(const Vec& lower, const Vec& upper, const Vec& guess);

 private:
  int nx_ = 0, nu_ = 0, npsi_ = 0, nc_ = 0;
  double t0_ = 0.0, tf_ = 1.0;
  Vec x0_;
  Vec terminal_weights_;
  bool terminal_weights_chosen_ = false;
  ControlSet control_set_;
  std::optional<FreeFinalTime> free_final_time_;
  std::optional<VectorBounds> state_bounds_;
  std::optional<VectorBounds> initial_state_bounds_;
  int nb_ = 0;
  VectorBounds boundary_bounds_;
  int np_ = 0;
  bool free_initial_state_ = false;
};

}  // namespace ocpb
