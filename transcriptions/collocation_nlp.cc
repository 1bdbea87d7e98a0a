#include "transcriptions/collocation_nlp.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/evaluator.h"
#include "transcriptions/simulation_mesh_error.h"
#include "transcriptions/sparse_builder.h"

namespace ocpb {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<int> Range(int begin, int size) {
  std::vector<int> r(size);
  for (int i = 0; i < size; ++i) r[i] = begin + i;
  return r;
}

}  // namespace

int CollocationLayout::AddState(double t, int interval_start) {
  StateBlock b;
  b.t = t;
  b.offset = num_variables;
  b.interval_start = interval_start;
  num_variables += nx;
  states.push_back(b);
  return static_cast<int>(states.size()) - 1;
}

int CollocationLayout::AddControl(double t) {
  ControlBlock b;
  b.t = t;
  b.offset = num_variables;
  num_variables += nu;
  controls.push_back(b);
  return static_cast<int>(controls.size()) - 1;
}

void ValidateTranscriptionOptions(const Ocp& ocp, const TranscriptionOptions& options) {
  if (const std::string off = ocp.GridOffHorizon(options.grid, Ocp::HorizonEnd::kNominal);
      !off.empty()) {
    throw std::invalid_argument("transcription: " + off);
  }
  if (options.initial_guess && options.initial_guess->nu() != ocp.nu()) {
    throw std::invalid_argument("transcription: the initial guess must have nu = " +
                                std::to_string(ocp.nu()) + " components");
  }
  std::string error;
  if ((options.initial_guess || options.initial_states) && !options.IsValidFor(ocp, &error)) {
    throw std::invalid_argument(error);
  }
  if (!options.scaling.IsValidFor(ocp.nx(), ocp.nu(), &error)) {
    throw std::invalid_argument("transcription: " + error);
  }
  ocp.CheckStaticParameterDynamics();
}

CollocationNlp::CollocationNlp(const Ocp& ocp,
                               const TranscriptionOptions& options,
                               CollocationLayout layout,
                               Integrator start_integrator)
    : ocp_(ocp),
      grid_(options.grid),
      mode_(options.terminal),
      mesh_estimate_(options.mesh.estimate),
      initial_guess_(options.initial_guess),
      initial_states_(options.initial_states),
      start_final_time_(options.GuessFinalTime(ocp)),
      layout_(std::move(layout)),
      start_integrator_(start_integrator),
      nx_(ocp.nx()),
      nu_(ocp.nu()),
      nc_(ocp.num_path()),
      npsi_(ocp.num_terminal()),
      nb_(ocp.num_boundary()) {
  if (layout_.nx != nx_ || layout_.nu != nu_ || layout_.states.size() < 2) {
    throw std::logic_error("CollocationNlp: layout does not match the problem");
  }
  std::vector<double> times;
  for (const auto& s : layout_.states) times.push_back(s.t);
  state_grid_ = TimeGrid::FromPoints(times);
  free_time_ = ocp.free_final_time().has_value();
  initial_cost_ = ocp.HasFreeInitialState() && ocp.HasInitialCost();
  time_index_ = free_time_ ? layout_.num_variables : -1;
  inv_duration_ = 1.0 / (grid_.tf() - grid_.t0());

  // Variable scales.
  objective_scale_ = options.scaling.objective;
  const Vec sx = options.scaling.state.size() ? options.scaling.state : Vec::Ones(nx_);
  const Vec su = options.scaling.control.size() ? options.scaling.control : Vec::Ones(nu_);
  var_scale_ = Vec::Ones(num_variables());  // T, when a variable, is not scaled
  for (const auto& s : layout_.states) var_scale_.segment(s.offset, nx_) = sx;
  for (const auto& c : layout_.controls) var_scale_.segment(c.offset, nu_) = su;

  // Rows.
  const int num_defect_rows = static_cast<int>(layout_.defects.size()) * nx_;
  path_row_begin_ = num_defect_rows;
  path_point_row_.assign(layout_.points.size(), -1);
  int row = path_row_begin_;
  if (nc_ > 0) {
    for (size_t e = 0; e < layout_.points.size(); ++e) {
      if (layout_.points[e].path) {
        path_point_row_[e] = row;
        row += nc_;
      }
    }
  }
  ball_row_begin_ = row;
  const auto& blocks = ocp_.control_set().blocks();
  for (size_t b = 0; b < blocks.size(); ++b) {
    if (blocks[b].kind == ControlSet::Kind::kBall) ball_blocks_.push_back(static_cast<int>(b));
  }
  row += static_cast<int>(layout_.controls.size() * ball_blocks_.size());
  terminal_row_begin_ = row;
  if (mode_ == TerminalMode::kHard) row += npsi_;
  boundary_row_begin_ = row;
  row += nb_;
  num_constraints_ = row;

  row_scale_ = Vec::Ones(num_constraints_);
  for (size_t d = 0; d < layout_.defects.size(); ++d) {
    row_scale_.segment(d * nx_, nx_) = sx.cwiseInverse();
  }
  BuildStructure();
  // The lower-triangle entries of each point's (nx + nu)^2 block, as (entry of H, slot).
  const int nz = nx_ + nu_;
  point_hess_pairs_begin_.push_back(0);
  for (size_t e = 0; e < layout_.points.size(); ++e) {
    for (int a = 0; a < nz; ++a) {
      for (int b = 0; b < nz; ++b) {
        const int slot = hess_slots_[point_hess_slots_[e] + a * nz + b];
        if (slot >= 0) point_hess_pairs_.push_back({b * nz + a, slot});  // H is column-major
      }
    }
    point_hess_pairs_begin_.push_back(static_cast<int>(point_hess_pairs_.size()));
  }
  // Affine dynamics on a fixed horizon: the defect rows' Jacobian does not depend on z (any z
  // gives it; the starting point's states are simulated, so use zeros), so it is computed once.
  if (ocp_.HasAffineDynamics() && !free_time_) {
    Vec defect = Vec::Zero(static_cast<Eigen::Index>(jac_rows_.size()));
    AddDefectJacobian(Vec::Zero(num_variables()), &defect);
    if (defect.allFinite()) scaled_defect_jacobian_ = defect.cwiseProduct(jac_value_scale_);
  }
}

void CollocationNlp::BuildStructure() {
  const int n = num_variables();
  const auto xcols = [&](int j) { return Range(layout_.states[j].offset, nx_); };
  const auto ucols = [&](int i) { return Range(layout_.controls[i].offset, nu_); };
  const auto append = [](std::vector<int>* pool, const std::vector<int>& slots) {
    const int base = static_cast<int>(pool->size());
    pool->insert(pool->end(), slots.begin(), slots.end());
    return base;
  };

  // ---- Jacobian ----
  TripletPattern jac(num_constraints_, n);
  point_uses_.assign(layout_.points.size(), {});
  for (size_t d = 0; d < layout_.defects.size(); ++d) {
    const auto& defect = layout_.defects[d];
    const std::vector<int> rows = Range(defect_row(static_cast<int>(d)), nx_);
    for (const auto& term : defect.states) {
      const int base = append(&jac_slots_, jac.Block(rows, xcols(term.index)));
      state_uses_.push_back({static_cast<int>(d), term.index, term.coeff, base});
    }
    for (const auto& term : defect.dynamics) {
      const auto& p = layout_.points[term.index];
      const int xb = append(&jac_slots_, jac.Block(rows, xcols(p.state)));
      const int ub = append(&jac_slots_, jac.Block(rows, ucols(p.control)));
      point_uses_[term.index].push_back({static_cast<int>(d), -term.coeff, xb, ub});
    }
  }
  path_x_slots_.assign(layout_.points.size(), -1);
  path_u_slots_.assign(layout_.points.size(), -1);
  for (size_t e = 0; e < layout_.points.size(); ++e) {
    if (path_point_row_[e] < 0) continue;
    const auto& p = layout_.points[e];
    const std::vector<int> rows = Range(path_point_row_[e], nc_);
    path_x_slots_[e] = append(&jac_slots_, jac.Block(rows, xcols(p.state)));
    path_u_slots_[e] = append(&jac_slots_, jac.Block(rows, ucols(p.control)));
  }
  const auto& blocks = ocp_.control_set().blocks();
  int row = ball_row_begin_;
  for (size_t i = 0; i < layout_.controls.size(); ++i) {
    for (int b : ball_blocks_) {
      const std::vector<int> cols =
          Range(layout_.controls[i].offset + blocks[b].offset, blocks[b].size);
      ball_slots_.push_back(append(&jac_slots_, jac.Block({row}, cols)));
      ++row;
    }
  }
  const int last = static_cast<int>(layout_.states.size()) - 1;
  if (mode_ == TerminalMode::kHard && npsi_ > 0) {
    terminal_slots_ =
        append(&jac_slots_, jac.Block(Range(terminal_row_begin_, npsi_), xcols(last)));
  }
  if (nb_ > 0) {
    const std::vector<int> rows = Range(boundary_row_begin_, nb_);
    boundary_x0_slots_ = append(&jac_slots_, jac.Block(rows, xcols(0)));
    boundary_xf_slots_ = append(&jac_slots_, jac.Block(rows, xcols(last)));
  }
  if (free_time_) {
    for (size_t d = 0; d < layout_.defects.size(); ++d) {
      time_jac_slots_.push_back(append(
          &jac_slots_, jac.Block(Range(defect_row(static_cast<int>(d)), nx_), {time_index_})));
    }
  }
  jac_rows_ = jac.rows();
  jac_cols_ = jac.cols();
  jac_value_scale_.resize(jac.size());
  for (int s = 0; s < jac.size(); ++s) {
    jac_value_scale_[s] = row_scale_[jac_rows_[s]] * var_scale_[jac_cols_[s]];
  }

  // ---- Hessian of the Lagrangian, lower triangle ----
  TripletPattern hess(n, n);
  for (const auto& p : layout_.points) {
    std::vector<int> cols = xcols(p.state);
    const std::vector<int> uc = ucols(p.control);
    cols.insert(cols.end(), uc.begin(), uc.end());
    point_hess_slots_.push_back(append(&hess_slots_, hess.Block(cols, cols, true)));
    if (free_time_) {  // T is the last variable: its row is in the lower triangle
      time_hess_slots_.push_back(append(&hess_slots_, hess.Block({time_index_}, cols, true)));
    }
  }
  terminal_hess_slots_ = append(&hess_slots_, hess.Block(xcols(last), xcols(last), true));
  if (initial_cost_) {
    initial_hess_slots_ = append(&hess_slots_, hess.Block(xcols(0), xcols(0), true));
  }
  if (nb_ > 0) {  // (x(t0), x(tf)) jointly: its lower triangle in the NLP's column order
    std::vector<int> ends = xcols(0);
    const std::vector<int> xf = xcols(last);
    ends.insert(ends.end(), xf.begin(), xf.end());
    boundary_hess_slots_ = append(&hess_slots_, hess.Block(ends, ends, true));
  }
  for (size_t i = 0; i < layout_.controls.size(); ++i) {
    for (int b : ball_blocks_) {
      std::vector<int> diag;
      for (int c = 0; c < blocks[b].size; ++c) {
        diag.push_back(hess.Slot(layout_.controls[i].offset + blocks[b].offset + c,
                                 layout_.controls[i].offset + blocks[b].offset + c));
      }
      ball_hess_slots_.push_back(append(&hess_slots_, diag));
    }
  }
  hess_rows_ = hess.rows();
  hess_cols_ = hess.cols();
  hess_value_scale_.resize(hess.size());
  for (int s = 0; s < hess.size(); ++s) {
    hess_value_scale_[s] = var_scale_[hess_rows_[s]] * var_scale_[hess_cols_[s]];
  }
}

// ---- bounds and starting point -------------------------------------------------------------

void CollocationNlp::Bounds(Vec* z_lower, Vec* z_upper, Vec* g_lower, Vec* g_upper) const {
  const int n = num_variables();
  Vec zl = Vec::Constant(n, -kInf), zu = Vec::Constant(n, kInf);
  // x(t0): fixed to x0, or within the initial-state bounds; every later state point within
  // the state bounds (Ocp's class comment).
  const VectorBounds initial = ocp_.InitialNodeBounds();
  const auto& x0_block = layout_.states.front();
  zl.segment(x0_block.offset, nx_) = initial.lower;
  zu.segment(x0_block.offset, nx_) = initial.upper;
  if (const auto& sb = ocp_.state_bounds()) {
    for (size_t j = 1; j < layout_.states.size(); ++j) {
      zl.segment(layout_.states[j].offset, nx_) = sb->lower;
      zu.segment(layout_.states[j].offset, nx_) = sb->upper;
    }
  }
  for (const auto& c : layout_.controls) {
    for (const auto& b : ocp_.control_set().blocks()) {
      if (b.kind != ControlSet::Kind::kBox) continue;
      zl.segment(c.offset + b.offset, b.size) = b.lower;
      zu.segment(c.offset + b.offset, b.size) = b.upper;
    }
  }
  if (free_time_) {
    zl[time_index_] = ocp_.free_final_time()->lower;
    zu[time_index_] = ocp_.free_final_time()->upper;
  }
  *z_lower = zl.cwiseQuotient(var_scale_);
  *z_upper = zu.cwiseQuotient(var_scale_);

  Vec gl = Vec::Zero(num_constraints_), gu = Vec::Zero(num_constraints_);
  for (int r = path_row_begin_; r < ball_row_begin_; ++r) gl[r] = -kInf;
  if (nb_ > 0) {
    gl.segment(boundary_row_begin_, nb_) = ocp_.boundary_bounds().lower;
    gu.segment(boundary_row_begin_, nb_) = ocp_.boundary_bounds().upper;
  }
  const auto& blocks = ocp_.control_set().blocks();
  int row = ball_row_begin_;
  for (size_t i = 0; i < layout_.controls.size(); ++i) {
    for (int b : ball_blocks_) {
      gl[row] = -kInf;
      gu[row] = blocks[b].radius * blocks[b].radius;
      ++row;
    }
  }
  *g_lower = gl.cwiseProduct(row_scale_);
  *g_upper = gu.cwiseProduct(row_scale_);
}

Vec CollocationNlp::StartingPoint() const {
  const ControlTrajectory guess = initial_guess_ ? *initial_guess_ : [&] {
    Vec u0 = ocp_.CheckedNominalControl();
    ocp_.control_set().Project(u0);
    return ControlTrajectory::Constant(grid_, u0);
  }();
  // A free final time starts at the guess's own T (a previous solution's): the layout's nominal
  // times are read on the guess's stretched axis t0 + r (t - t0).
  const bool stretched = free_time_ && start_final_time_ != grid_.tf();
  const double r = stretched ? (start_final_time_ - grid_.t0()) * inv_duration_ : 1.0;
  auto at = [&](double t) { return stretched ? grid_.t0() + r * (t - grid_.t0()) : t; };
  Mat values(nu_, layout_.controls.size());
  for (size_t i = 0; i < layout_.controls.size(); ++i) {
    const double t = layout_.controls[i].t;
    const auto side =
        t >= grid_.tf() ? ControlTrajectory::Side::kLeft : ControlTrajectory::Side::kRight;
    guess.Evaluate(at(t), side, values.col(i));
    ocp_.control_set().Project(values.col(i));
  }
  Mat X(nx_, state_grid_.size());
  if (initial_states_) {
    for (int j = 0; j < state_grid_.size(); ++j) {
      initial_states_->Evaluate(at(state_grid_.t(j)), ControlTrajectory::Side::kRight, X.col(j));
    }
  } else if (stretched) {
    X = Evaluate(ocp_,
                 MakeControls(values, grid_.StretchedTo(start_final_time_)),
                 state_grid_.StretchedTo(start_final_time_),
                 start_integrator_)
            .X;
  } else {
    X = Evaluate(ocp_, MakeControls(values, grid_), state_grid_, start_integrator_).X;
  }
  if (!X.allFinite()) X = ocp_.x0().replicate(1, state_grid_.size());

  Vec z = Vec::Zero(num_variables());
  if (free_time_) z[time_index_] = start_final_time_;
  for (size_t j = 0; j < layout_.states.size(); ++j) {
    z.segment(layout_.states[j].offset, nx_) = X.col(j);
  }
  for (size_t i = 0; i < layout_.controls.size(); ++i) {
    z.segment(layout_.controls[i].offset, nu_) = values.col(i);
  }
  return Scale(z);
}

// ---- recovery ------------------------------------------------------------------------------

Mat CollocationNlp::ControlValues(ConstVecRef zhat) const {
  Mat values(nu_, layout_.controls.size());
  for (size_t i = 0; i < layout_.controls.size(); ++i) {
    const int o = layout_.controls[i].offset;
    values.col(i) = zhat.segment(o, nu_).cwiseProduct(var_scale_.segment(o, nu_));
  }
  return values;
}

double CollocationNlp::Ratio(const Vec& z) const {
  return free_time_ ? (z[time_index_] - grid_.t0()) * inv_duration_ : 1.0;
}

double CollocationNlp::FinalTime(ConstVecRef zhat) const {
  return free_time_ ? zhat[time_index_] * var_scale_[time_index_] : grid_.tf();
}

TimeGrid CollocationNlp::StateGrid(ConstVecRef zhat) const {
  return free_time_ ? state_grid_.StretchedTo(FinalTime(zhat)) : state_grid_;
}

ControlTrajectory CollocationNlp::Controls(ConstVecRef zhat) const {
  // With a free final time the scheme's own interpolation on the stretched mesh: mapping times
  // back to the nominal mesh instead would put stretched nodes an ulp into the wrong interval.
  return MakeControls(ControlValues(zhat), free_time_ ? grid_.StretchedTo(FinalTime(zhat)) : grid_);
}

Mat CollocationNlp::States(ConstVecRef zhat) const {
  Mat X(nx_, layout_.states.size());
  for (size_t j = 0; j < layout_.states.size(); ++j) {
    const int o = layout_.states[j].offset;
    X.col(j) = zhat.segment(o, nx_).cwiseProduct(var_scale_.segment(o, nx_));
  }
  return X;
}

TimeGrid CollocationNlp::SolutionMesh(ConstVecRef zhat) const {
  return free_time_ ? grid_.StretchedTo(FinalTime(zhat)) : grid_;
}

Mat CollocationNlp::NodeStates(ConstVecRef zhat) const {
  Mat X(nx_, grid_.size());
  for (const CollocationLayout::StateBlock& b : layout_.states) {
    if (b.interval_start < 0) continue;
    X.col(b.interval_start) =
        zhat.segment(b.offset, nx_).cwiseProduct(var_scale_.segment(b.offset, nx_));
  }
  return X;
}

Vec CollocationNlp::IntervalErrors(ConstVecRef zhat) const {
  if (mesh_estimate_ == MeshErrorEstimate::kSimulation) {
    return IntervalSimulationErrors(
        ocp_, SolutionMesh(zhat), StateGrid(zhat), States(zhat), Controls(zhat));
  }
  return SchemeIntervalErrors(zhat);
}

Vec CollocationNlp::SchemeIntervalErrors(ConstVecRef zhat) const {
  const std::optional<CollocationInterpolant> scheme = mesh_interpolant();
  if (!scheme) return Vec();
  return IntervalDefectErrors(ocp_, *scheme, SolutionMesh(zhat), NodeStates(zhat), Controls(zhat));
}

int CollocationNlp::IntervalErrorOrder() const {
  const std::optional<CollocationInterpolant> scheme = mesh_interpolant();
  return scheme ? DefectEstimateOrder(*scheme) : 0;
}

ControlTrajectory CollocationNlp::StateTrajectory(ConstVecRef zhat) const {
  const std::optional<CollocationInterpolant> scheme = mesh_interpolant();
  if (!scheme) return TranscribedNlp::StateTrajectory(zhat);
  return StateInterpolant(ocp_, *scheme, SolutionMesh(zhat), NodeStates(zhat), Controls(zhat));
}

Mat CollocationNlp::Costates(ConstVecRef zhat, ConstVecRef lambda_hat) const {
  if (lambda_hat.size() != num_constraints_) return Mat();
  const Vec z = Unscale(zhat);
  // Multipliers of the physical Lagrangian J + lambda^T g.
  const Vec lambda = lambda_hat.cwiseProduct(row_scale_) / objective_scale_;
  const double r = Ratio(z);  // the step lengths' factor at T (1 for a fixed horizon)
  const int S = static_cast<int>(layout_.states.size());
  Mat P = Mat::Zero(nx_, S);
  auto x_of = [&](int j) { return z.segment(layout_.states[j].offset, nx_); };
  auto u_of = [&](int i) { return z.segment(layout_.controls[i].offset, nu_); };
  auto start = [&](int j) { return layout_.states[j].interval_start; };
  auto future = [&](int j, int d) {
    return start(j) >= 0 && layout_.defects[d].interval >= start(j);
  };

  // Interval starts: gradient of the cost-to-go part of the Lagrangian.
  for (const auto& use : state_uses_) {
    if (future(use.state, use.defect)) {
      P.col(use.state) += use.coeff * lambda.segment(defect_row(use.defect), nx_);
    }
  }
  Vec f(nx_), Lx(nx_), Lu(nu_), c(nc_);
  Mat fx(nx_, nx_), fu(nx_, nu_), cx(nc_, nx_), cu(nc_, nu_);
  double L;
  for (size_t e = 0; e < layout_.points.size(); ++e) {
    const auto& p = layout_.points[e];
    if (start(p.state) < 0) continue;
    ocp_.DynamicsJacobian(p.t, x_of(p.state), u_of(p.control), f, fx, fu);
    for (const auto& use : point_uses_[e]) {
      if (future(p.state, use.defect)) {
        P.col(p.state) +=
            r * use.coeff * fx.transpose() * lambda.segment(defect_row(use.defect), nx_);
      }
    }
    if (p.future_cost_weight != 0.0) {
      ocp_.RunningCostGradient(p.t, x_of(p.state), u_of(p.control), &L, Lx, Lu);
      P.col(p.state) += r * p.future_cost_weight * Lx;
    }
    if (path_point_row_[e] >= 0) {
      ocp_.PathConstraintsJacobian(p.t, x_of(p.state), u_of(p.control), c, cx, cu);
      P.col(p.state) += cx.transpose() * lambda.segment(path_point_row_[e], nc_);
    }
  }
  // The final state: the terminal terms.
  const int last = S - 1;
  double phi;
  Vec grad(nx_);
  ocp_.TerminalObjectiveGradient(x_of(last), mode_, &phi, grad);
  P.col(last) += grad;
  if (mode_ == TerminalMode::kHard && npsi_ > 0) {
    Vec psi(npsi_);
    Mat psix(npsi_, nx_);
    ocp_.TerminalConstraintsJacobian(x_of(last), psi, psix);
    P.col(last) += psix.transpose() * lambda.segment(terminal_row_begin_, npsi_);
  }
  if (nb_ > 0) {  // x(tf)'s part of the boundary constraints closes the cost-to-go at tf
    Vec b(nb_);
    Mat b0(nb_, nx_), bf(nb_, nx_);
    ocp_.BoundaryConstraintsJacobian(x_of(0), x_of(last), b, b0, bf);
    P.col(last) += bf.transpose() * lambda.segment(boundary_row_begin_, nb_);
  }
  // Blocks inside an interval: a scaled defect multiplier plus interval-start costates.
  for (int j = 0; j < S; ++j) {
    const auto& b = layout_.states[j];
    if (b.interval_start >= 0) continue;
    if (b.costate_defect >= 0) {
      P.col(j) = b.costate_scale * lambda.segment(defect_row(b.costate_defect), nx_);
    }
    for (const auto& term : b.costate_blocks) P.col(j) += term.coeff * P.col(term.index);
  }
  return P;
}

// ---- scaled interface ----------------------------------------------------------------------

bool CollocationNlp::Objective(ConstVecRef zhat, double* f) const {
  double J;
  if (!EvalObjective(Unscale(zhat), &J)) return false;
  *f = objective_scale_ * J;
  return true;
}

bool CollocationNlp::Gradient(ConstVecRef zhat, VecRef grad) const {
  Vec g;
  if (!EvalGradient(Unscale(zhat), &g)) return false;
  grad = objective_scale_ * g.cwiseProduct(var_scale_);
  return true;
}

bool CollocationNlp::Constraints(ConstVecRef zhat, VecRef g) const {
  Vec out;
  if (!EvalConstraints(Unscale(zhat), &out)) return false;
  g = out.cwiseProduct(row_scale_);
  return true;
}

bool CollocationNlp::JacobianValues(ConstVecRef zhat, VecRef values) const {
  if (scaled_defect_jacobian_.size() > 0) {
    // Affine dynamics: the defect rows were computed and scaled once; only the other rows
    // (balls, path constraints, hard terminal constraints, boundary constraints) depend on z.
    values = scaled_defect_jacobian_;
    return AddOtherJacobianRows(Unscale(zhat), jac_value_scale_.data(), values.data());
  }
  Vec out;
  if (!EvalJacobian(Unscale(zhat), &out)) return false;
  values = out.cwiseProduct(jac_value_scale_);
  return true;
}

bool CollocationNlp::HessianValues(ConstVecRef zhat,
                                   double sigma,
                                   ConstVecRef lambda_hat,
                                   VecRef values) const {
  Vec out;
  if (!EvalHessian(
          Unscale(zhat), sigma * objective_scale_, lambda_hat.cwiseProduct(row_scale_), &out)) {
    return false;
  }
  values = out.cwiseProduct(hess_value_scale_);
  return true;
}

// ---- physical evaluations ------------------------------------------------------------------

bool CollocationNlp::EvalObjective(const Vec& z, double* f) const {
  double sum = 0.0;
  const double r = Ratio(z);
  for (const auto& p : layout_.points) {
    if (p.cost_weight == 0.0) continue;
    sum += p.cost_weight * ocp_.RunningCost(p.t,
                                            z.segment(layout_.states[p.state].offset, nx_),
                                            z.segment(layout_.controls[p.control].offset, nu_));
  }
  sum = r * sum + ocp_.TerminalObjective(z.segment(layout_.states.back().offset, nx_), mode_);
  if (initial_cost_) sum += ocp_.InitialCost(z.segment(layout_.states.front().offset, nx_));
  *f = sum;
  return std::isfinite(sum);
}

bool CollocationNlp::EvalGradient(const Vec& z, Vec* grad) const {
  grad->setZero(num_variables());
  Vec Lx(nx_), Lu(nu_);
  double L;
  const double r = Ratio(z);
  double running = 0.0;  // sum_e w_e L_e at the nominal weights
  for (const auto& p : layout_.points) {
    if (p.cost_weight == 0.0) continue;
    const int xo = layout_.states[p.state].offset, uo = layout_.controls[p.control].offset;
    ocp_.RunningCostGradient(p.t, z.segment(xo, nx_), z.segment(uo, nu_), &L, Lx, Lu);
    grad->segment(xo, nx_) += r * p.cost_weight * Lx;
    grad->segment(uo, nu_) += r * p.cost_weight * Lu;
    running += p.cost_weight * L;
  }
  if (free_time_) (*grad)[time_index_] = inv_duration_ * running;
  const int xo = layout_.states.back().offset;
  double phi;
  Vec g(nx_);
  ocp_.TerminalObjectiveGradient(z.segment(xo, nx_), mode_, &phi, g);
  grad->segment(xo, nx_) += g;
  if (initial_cost_) {
    const int x0o = layout_.states.front().offset;
    ocp_.InitialCostGradient(z.segment(x0o, nx_), &phi, g);
    grad->segment(x0o, nx_) += g;
  }
  return grad->allFinite();
}

bool CollocationNlp::EvalConstraints(const Vec& z, Vec* g) const {
  g->setZero(num_constraints_);
  for (const auto& use : state_uses_) {
    g->segment(defect_row(use.defect), nx_) +=
        use.coeff * z.segment(layout_.states[use.state].offset, nx_);
  }
  Vec f(nx_), c(nc_);
  const double r = Ratio(z);
  for (size_t e = 0; e < layout_.points.size(); ++e) {
    const auto& p = layout_.points[e];
    const auto x = z.segment(layout_.states[p.state].offset, nx_);
    const auto u = z.segment(layout_.controls[p.control].offset, nu_);
    if (!point_uses_[e].empty()) {
      ocp_.Dynamics(p.t, x, u, f);
      for (const auto& use : point_uses_[e])
        g->segment(defect_row(use.defect), nx_) += r * use.coeff * f;
    }
    if (path_point_row_[e] >= 0) {
      ocp_.PathConstraints(p.t, x, u, c);
      g->segment(path_point_row_[e], nc_) = c;
    }
  }
  const auto& blocks = ocp_.control_set().blocks();
  int row = ball_row_begin_;
  for (const auto& cb : layout_.controls) {
    for (int b : ball_blocks_) {
      (*g)[row++] = (z.segment(cb.offset + blocks[b].offset, blocks[b].size) - blocks[b].center)
                        .squaredNorm();
    }
  }
  if (mode_ == TerminalMode::kHard && npsi_ > 0) {
    Vec psi(npsi_);
    ocp_.TerminalConstraints(z.segment(layout_.states.back().offset, nx_), psi);
    g->segment(terminal_row_begin_, npsi_) = psi;
  }
  if (nb_ > 0) {
    Vec b(nb_);
    ocp_.BoundaryConstraints(z.segment(layout_.states.front().offset, nx_),
                             z.segment(layout_.states.back().offset, nx_),
                             b);
    g->segment(boundary_row_begin_, nb_) = b;
  }
  return g->allFinite();
}

bool CollocationNlp::EvalJacobian(const Vec& z, Vec* values) const {
  values->setZero(static_cast<Eigen::Index>(jac_rows_.size()));
  AddDefectJacobian(z, values);
  AddOtherJacobianRows(z, nullptr, values->data());
  return values->allFinite();
}

bool CollocationNlp::AddOtherJacobianRows(const Vec& z, const double* scale, double* v) const {
  // Each slot of these rows gets exactly one term, so adding scale * term to a zero entry gives
  // the same double as scaling the finished sum (the order EvalJacobian's callers use).
  bool finite = true;
  auto add = [&](int slot, double term) {
    v[slot] += scale == nullptr ? term : term * scale[slot];
    finite = finite && std::isfinite(term);
  };
  Vec c(nc_);
  Mat cx(nc_, nx_), cu(nc_, nu_);
  for (size_t e = 0; e < layout_.points.size(); ++e) {
    const auto& p = layout_.points[e];
    if (path_point_row_[e] >= 0) {
      const auto x = z.segment(layout_.states[p.state].offset, nx_);
      const auto u = z.segment(layout_.controls[p.control].offset, nu_);
      ocp_.PathConstraintsJacobian(p.t, x, u, c, cx, cu);
      for (int i = 0; i < nc_; ++i) {
        for (int j = 0; j < nx_; ++j) add(jac_slots_[path_x_slots_[e] + i * nx_ + j], cx(i, j));
        for (int j = 0; j < nu_; ++j) add(jac_slots_[path_u_slots_[e] + i * nu_ + j], cu(i, j));
      }
    }
  }
  const auto& blocks = ocp_.control_set().blocks();
  int ball = 0;
  for (const auto& cb : layout_.controls) {
    for (int b : ball_blocks_) {
      const int base = ball_slots_[ball++];
      for (int j = 0; j < blocks[b].size; ++j) {
        add(jac_slots_[base + j],
            2.0 * (z[cb.offset + blocks[b].offset + j] - blocks[b].center[j]));
      }
    }
  }
  if (terminal_slots_ >= 0) {
    Vec psi(npsi_);
    Mat psix(npsi_, nx_);
    ocp_.TerminalConstraintsJacobian(z.segment(layout_.states.back().offset, nx_), psi, psix);
    for (int i = 0; i < npsi_; ++i) {
      for (int j = 0; j < nx_; ++j) add(jac_slots_[terminal_slots_ + i * nx_ + j], psix(i, j));
    }
  }
  if (nb_ > 0) {
    Vec b(nb_);
    Mat b0(nb_, nx_), bf(nb_, nx_);
    ocp_.BoundaryConstraintsJacobian(z.segment(layout_.states.front().offset, nx_),
                                     z.segment(layout_.states.back().offset, nx_),
                                     b,
                                     b0,
                                     bf);
    for (int i = 0; i < nb_; ++i) {
      for (int j = 0; j < nx_; ++j) {
        add(jac_slots_[boundary_x0_slots_ + i * nx_ + j], b0(i, j));
        add(jac_slots_[boundary_xf_slots_ + i * nx_ + j], bf(i, j));
      }
    }
  }
  return finite;
}

void CollocationNlp::AddDefectJacobian(const Vec& z, Vec* values) const {
  Vec& v = *values;
  for (const auto& use : state_uses_) {
    for (int i = 0; i < nx_; ++i) v[jac_slots_[use.x_slots + i * nx_ + i]] += use.coeff;
  }
  Vec f(nx_);
  Mat fx(nx_, nx_), fu(nx_, nu_);
  const double r = Ratio(z);
  for (size_t e = 0; e < layout_.points.size(); ++e) {
    const auto& p = layout_.points[e];
    const auto x = z.segment(layout_.states[p.state].offset, nx_);
    const auto u = z.segment(layout_.controls[p.control].offset, nu_);
    if (!point_uses_[e].empty()) {
      ocp_.DynamicsJacobian(p.t, x, u, f, fx, fu);
      for (const auto& use : point_uses_[e]) {
        const double a = r * use.coeff;
        for (int i = 0; i < nx_; ++i) {
          for (int j = 0; j < nx_; ++j) v[jac_slots_[use.x_slots + i * nx_ + j]] += a * fx(i, j);
          for (int j = 0; j < nu_; ++j) v[jac_slots_[use.u_slots + i * nu_ + j]] += a * fu(i, j);
        }
        if (free_time_) {
          const int base = time_jac_slots_[use.defect];
          for (int i = 0; i < nx_; ++i) v[jac_slots_[base + i]] += inv_duration_ * use.coeff * f[i];
        }
      }
    }
  }
}

bool CollocationNlp::EvalHessian(const Vec& z, double sigma, const Vec& lambda, Vec* values) const {
  values->setZero(static_cast<Eigen::Index>(hess_rows_.size()));
  Vec& v = *values;
  const int nz = nx_ + nu_;
  // Plain loops over preallocated storage: this loop runs at every point of every Ipopt
  // iteration, and Eigen's dynamic-size temporaries (a Ref of an expression allocates) cost
  // more than the problem's own closed-form Hessian.
  Vec lam(nx_), scaled_lam(nx_), mu = Vec::Zero(nc_);
  Mat H(nz, nz);
  const double r = Ratio(z);
  Vec f(nx_), Lx(nx_), Lu(nu_);
  Mat fx(nx_, nx_), fu(nx_, nu_);
  double L = 0.0;
  for (size_t e = 0; e < layout_.points.size(); ++e) {
    const auto& p = layout_.points[e];
    bool any_lam = false;
    for (int i = 0; i < nx_; ++i) {
      double sum = 0.0;
      for (const auto& use : point_uses_[e]) sum += use.coeff * lambda[defect_row(use.defect) + i];
      lam[i] = sum;
      any_lam = any_lam || sum != 0.0;
    }
    bool any_mu = false;
    for (int i = 0; i < nc_; ++i) {
      mu[i] = path_point_row_[e] >= 0 ? lambda[path_point_row_[e] + i] : 0.0;
      any_mu = any_mu || mu[i] != 0.0;
    }
    const double s = sigma * p.cost_weight;
    if (s == 0.0 && !any_lam && !any_mu) continue;
    const auto x = z.segment(layout_.states[p.state].offset, nx_);
    const auto u = z.segment(layout_.controls[p.control].offset, nu_);
    if (free_time_) {
      // d^2/dT d(x, u) = (1 / (tf - t0)) grad_(x,u) (s L + lam^T f), at the nominal weights.
      ocp_.DynamicsJacobian(p.t, x, u, f, fx, fu);
      ocp_.RunningCostGradient(p.t, x, u, &L, Lx, Lu);
      const int base = time_hess_slots_[e];
      for (int j = 0; j < nx_; ++j) {
        v[hess_slots_[base + j]] += inv_duration_ * (s * Lx[j] + fx.col(j).dot(lam));
      }
      for (int j = 0; j < nu_; ++j) {
        v[hess_slots_[base + nx_ + j]] += inv_duration_ * (s * Lu[j] + fu.col(j).dot(lam));
      }
    }
    for (int i = 0; i < nx_; ++i) scaled_lam[i] = r * lam[i];
    ocp_.PointHessian(p.t, x, u, r * s, scaled_lam, mu, H);
    const double* h = H.data();
    for (int k = point_hess_pairs_begin_[e]; k < point_hess_pairs_begin_[e + 1]; ++k) {
      v[point_hess_pairs_[k].slot] += h[point_hess_pairs_[k].entry];
    }
  }
  // Terminal terms.
  const auto xN = z.segment(layout_.states.back().offset, nx_);
  Mat T(nx_, nx_);
  if (mode_ == TerminalMode::kPenalty && npsi_ > 0) {
    // sigma (phi + sum w_i psi_i^2): second derivative sigma phi'' + sum 2 sigma w_i psi_i psi_i''
    // + 2 sigma psi_x^T W psi_x.
    Vec psi(npsi_);
    Mat psix(npsi_, nx_);
    ocp_.TerminalConstraintsJacobian(xN, psi, psix);
    const Vec w = ocp_.terminal_weights();
    ocp_.TerminalHessian(xN, sigma, 2.0 * sigma * w.cwiseProduct(psi), T);
    T += 2.0 * sigma * psix.transpose() * w.asDiagonal() * psix;
  } else if (mode_ == TerminalMode::kHard && npsi_ > 0) {
    ocp_.TerminalHessian(xN, sigma, lambda.segment(terminal_row_begin_, npsi_), T);
  } else {
    ocp_.TerminalHessian(xN, sigma, Vec::Zero(npsi_), T);
  }
  for (int a = 0; a < nx_; ++a) {
    for (int b = 0; b < nx_; ++b) {
      const int slot = hess_slots_[terminal_hess_slots_ + a * nx_ + b];
      if (slot >= 0) v[slot] += T(a, b);
    }
  }
  if (nb_ > 0) {
    const int n2 = 2 * nx_;
    Mat B(n2, n2);
    ocp_.BoundaryHessian(z.segment(layout_.states.front().offset, nx_),
                         xN,
                         lambda.segment(boundary_row_begin_, nb_),
                         B);
    for (int a = 0; a < n2; ++a) {
      for (int b = 0; b < n2; ++b) {
        const int slot = hess_slots_[boundary_hess_slots_ + a * n2 + b];
        if (slot >= 0) v[slot] += B(a, b);
      }
    }
  }
  if (initial_cost_) {
    ocp_.InitialCostHessian(z.segment(layout_.states.front().offset, nx_), sigma, T);
    for (int a = 0; a < nx_; ++a) {
      for (int b = 0; b < nx_; ++b) {
        const int slot = hess_slots_[initial_hess_slots_ + a * nx_ + b];
        if (slot >= 0) v[slot] += T(a, b);
      }
    }
  }
  // Balls: |u_b - c|^2 has Hessian 2 I.
  const auto& blocks = ocp_.control_set().blocks();
  int row = ball_row_begin_, ball = 0;
  for (size_t i = 0; i < layout_.controls.size(); ++i) {
    for (int b : ball_blocks_) {
      const double m = lambda[row++];
      const int base = ball_hess_slots_[ball++];
      for (int j = 0; j < blocks[b].size; ++j) v[hess_slots_[base + j]] += 2.0 * m;
    }
  }
  return v.allFinite();
}

}  // namespace ocpb
