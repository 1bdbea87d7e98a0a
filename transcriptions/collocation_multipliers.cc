// CollocationNlp's multipliers as functions of time, and back onto another mesh: the costate map
// of Costates() read in reverse (transcriptions/multiplier_trajectories.h).
#include <algorithm>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/LU>

#include "transcriptions/collocation_nlp.h"
#include "transcriptions/radau_nodes.h"

namespace ocpb {
namespace {

// One mesh interval's costates: the Lagrange polynomial through its state points and the next
// interval's first, in the local coordinate s = 2 (t - a) / (b - a) - 1 on [a, b].
struct CostatePiece {
  double a = 0.0, b = 0.0;
  Vec s;        // the points' local coordinates
  Vec weights;  // their barycentric weights
  Mat values;   // nx x points
};

ControlTrajectory PiecewiseCostates(const TimeGrid& breaks,
                                    std::shared_ptr<const std::vector<CostatePiece>> pieces) {
  const int nx = static_cast<int>(pieces->front().values.rows());
  auto fn = [breaks, pieces](double t, ControlTrajectory::Side side, VecRef p) {
    int k = breaks.Locate(t);
    if (side == ControlTrajectory::Side::kLeft && k > 0 && t <= breaks.t(k)) --k;
    const CostatePiece& piece = (*pieces)[k];
    const double s = std::clamp(2.0 * (t - piece.a) / (piece.b - piece.a) - 1.0, -1.0, 1.0);
    Vec basis(piece.s.size());
    LagrangeBasis(piece.s, piece.weights, s, basis);
    p = piece.values * basis;
  };
  return ControlTrajectory::Custom(
      nx, breaks, fn, "costates: Lagrange polynomial through each mesh interval's state points");
}

// Densities (columns of `values`) at strictly increasing `times`, piecewise linear (constant
// for one point); nullopt when the times do not increase.
std::optional<ControlTrajectory> DensityTrajectory(const std::vector<double>& times,
                                                   const Mat& values,
                                                   double t0,
                                                   double tf) {
  if (times.empty() || values.rows() == 0) return ControlTrajectory();
  if (times.size() == 1) {
    return ControlTrajectory::Constant(TimeGrid::FromPoints({t0, tf}), values.col(0));
  }
  for (size_t i = 1; i < times.size(); ++i) {
    if (!(times[i] > times[i - 1])) return std::nullopt;
  }
  return ControlTrajectory::PiecewiseLinear(TimeGrid::FromPoints(times), values);
}

}  // namespace

std::optional<MultiplierTrajectories> CollocationNlp::MultiplierTrajectoriesAt(
    ConstVecRef zhat, const NlpMultipliers& y) const {
  if (!y.Fits(num_variables(), num_constraints_)) return std::nullopt;
  const Mat P = Costates(zhat, y.lambda);
  if (P.size() == 0 || !P.allFinite()) return std::nullopt;
  const Vec z = Unscale(zhat);
  const double r = Ratio(z);
  const double t0 = grid_.t0();
  auto at = [&](double t) { return t0 + r * (t - t0); };  // the solution's time axis
  // Physical multipliers (the scaling undone, as in Costates()).
  const Vec lambda = y.lambda.cwiseProduct(row_scale_) / objective_scale_;
  const Vec bound_scale = objective_scale_ * var_scale_;
  const Vec z_lower = y.z_lower.cwiseQuotient(bound_scale);
  const Vec z_upper = y.z_upper.cwiseQuotient(bound_scale);

  MultiplierTrajectories out;
  // Costates, one Lagrange piece per mesh interval (state blocks from one interval start to the
  // next).
  const int S = static_cast<int>(layout_.states.size());
  auto pieces = std::make_shared<std::vector<CostatePiece>>();
  std::vector<double> breaks;
  int first = 0;
  for (int j = 1; j < S; ++j) {
    if (layout_.states[j].interval_start < 0) continue;
    CostatePiece piece;
    piece.a = at(layout_.states[first].t);
    piece.b = at(layout_.states[j].t);
    if (!(piece.b > piece.a)) return std::nullopt;
    const int count = j - first + 1;
    piece.s.resize(count);
    for (int i = 0; i < count; ++i) {
      piece.s[i] = 2.0 * (at(layout_.states[first + i].t) - piece.a) / (piece.b - piece.a) - 1.0;
    }
    piece.weights = BarycentricWeights(piece.s);
    piece.values = P.middleCols(first, count);
    breaks.push_back(piece.a);
    pieces->push_back(std::move(piece));
    first = j;
  }
  if (pieces->empty() || first != S - 1) return std::nullopt;
  breaks.push_back(pieces->back().b);
  out.costates = PiecewiseCostates(TimeGrid::FromPoints(breaks), pieces);

  // Densities: a multiplier over its point's weight r w_e.
  const double tf = at(grid_.tf());
  std::vector<double> weight_of_control(layout_.controls.size(), 0.0);
  for (const auto& p : layout_.points) weight_of_control[p.control] += p.cost_weight;
  std::vector<double> times;
  if (nc_ > 0) {
    std::vector<int> path_points;
    for (size_t e = 0; e < layout_.points.size(); ++e) {
      if (path_point_row_[e] >= 0) path_points.push_back(static_cast<int>(e));
    }
    Mat values(nc_, static_cast<Eigen::Index>(path_points.size()));
    for (size_t i = 0; i < path_points.size(); ++i) {
      const int e = path_points[i];
      const double w = r * layout_.points[e].cost_weight;
      if (!(w > 0.0)) return std::nullopt;
      times.push_back(at(layout_.points[e].t));
      values.col(static_cast<Eigen::Index>(i)) = lambda.segment(path_point_row_[e], nc_) / w;
    }
    auto path = DensityTrajectory(times, values, t0, tf);
    if (!path) return std::nullopt;
    out.path = std::move(*path);
  }
  const int nc = static_cast<int>(layout_.controls.size());
  const int nb = static_cast<int>(ball_blocks_.size());
  times.clear();
  Mat balls(nb, nc), lower(nu_, nc), upper(nu_, nc);
  for (int i = 0; i < nc; ++i) {
    const double w = r * weight_of_control[i];
    if (!(w > 0.0)) return std::nullopt;
    times.push_back(at(layout_.controls[i].t));
    for (int b = 0; b < nb; ++b) balls(b, i) = lambda[ball_row_begin_ + i * nb + b] / w;
    lower.col(i) = z_lower.segment(layout_.controls[i].offset, nu_) / w;
    upper.col(i) = z_upper.segment(layout_.controls[i].offset, nu_) / w;
  }
  auto ball_density = DensityTrajectory(times, balls, t0, tf);
  auto lower_density = DensityTrajectory(times, lower, t0, tf);
  auto upper_density = DensityTrajectory(times, upper, t0, tf);
  if (!ball_density || !lower_density || !upper_density) return std::nullopt;
  out.balls = std::move(*ball_density);
  out.control_lower = std::move(*lower_density);
  out.control_upper = std::move(*upper_density);

  if (mode_ == TerminalMode::kHard && npsi_ > 0) {
    out.terminal = lambda.segment(terminal_row_begin_, npsi_);
  }
  if (free_time_) {
    out.final_time_lower = z_lower[time_index_];
    out.final_time_upper = z_upper[time_index_];
  }
  return out;
}

NlpMultipliers CollocationNlp::StartingMultipliers(ConstVecRef zhat0,
                                                   const MultiplierTrajectories& from) const {
  const int n = num_variables();
  const int S = static_cast<int>(layout_.states.size());
  const int D = static_cast<int>(layout_.defects.size());
  const int nb = static_cast<int>(ball_blocks_.size());
  const bool hard = mode_ == TerminalMode::kHard && npsi_ > 0;
  if (from.costates.nu() != nx_ || (nc_ > 0 && from.path.nu() != nc_) ||
      (nb > 0 && from.balls.nu() != nb) || from.control_lower.nu() != nu_ ||
      from.control_upper.nu() != nu_ || (hard && from.terminal.size() != npsi_)) {
    return NlpMultipliers();
  }
  const Vec z = Unscale(zhat0);
  const double r = Ratio(z);
  const double t0 = grid_.t0();
  auto at = [&](double t) { return t0 + r * (t - t0); };  // z0's time axis
  using Side = ControlTrajectory::Side;

  // p at every state point (the left limit at tf).
  Mat P(nx_, S);
  for (int j = 0; j < S; ++j) {
    from.costates.Evaluate(
        at(layout_.states[j].t), j == S - 1 ? Side::kLeft : Side::kRight, P.col(j));
  }
  // Physical multipliers: path, balls, terminal; defects below.
  Vec lambda = Vec::Zero(num_constraints_);
  Vec density(std::max({nc_, nb, nu_, 1}));
  for (size_t e = 0; e < layout_.points.size(); ++e) {
    if (path_point_row_[e] < 0) continue;
    from.path.Evaluate(at(layout_.points[e].t), Side::kRight, density.head(nc_));
    lambda.segment(path_point_row_[e], nc_) = r * layout_.points[e].cost_weight * density.head(nc_);
  }
  std::vector<double> weight_of_control(layout_.controls.size(), 0.0);
  for (const auto& p : layout_.points) weight_of_control[p.control] += p.cost_weight;
  Vec z_lower = Vec::Zero(n), z_upper = Vec::Zero(n);
  for (size_t i = 0; i < layout_.controls.size(); ++i) {
    const double t = at(layout_.controls[i].t);
    const double w = r * weight_of_control[i];
    if (nb > 0) {
      from.balls.Evaluate(t, Side::kRight, density.head(nb));
      lambda.segment(ball_row_begin_ + static_cast<int>(i) * nb, nb) = w * density.head(nb);
    }
    from.control_lower.Evaluate(t, Side::kRight, density.head(nu_));
    z_lower.segment(layout_.controls[i].offset, nu_) = w * density.head(nu_);
    from.control_upper.Evaluate(t, Side::kRight, density.head(nu_));
    z_upper.segment(layout_.controls[i].offset, nu_) = w * density.head(nu_);
  }
  if (hard) lambda.segment(terminal_row_begin_, npsi_) = from.terminal;
  if (free_time_) {
    z_lower[time_index_] = from.final_time_lower;
    z_upper[time_index_] = from.final_time_upper;
  }

  // Defects: first those an interior state point's costate names (Costates(): p_j =
  // costate_scale lambda_d + sum_c c p_c), then, per interval, the one left from the interval
  // start's relation p_j = sum (defect terms of intervals >= k) + r w Lx + cx^T mu.
  std::vector<char> known(D, 0);
  for (int j = 0; j < S; ++j) {
    const auto& b = layout_.states[j];
    if (b.interval_start >= 0 || b.costate_defect < 0) continue;
    if (b.costate_scale == 0.0 || known[b.costate_defect]) return NlpMultipliers();
    Vec rhs = P.col(j);
    for (const auto& term : b.costate_blocks) rhs -= term.coeff * P.col(term.index);
    lambda.segment(defect_row(b.costate_defect), nx_) = rhs / b.costate_scale;
    known[b.costate_defect] = 1;
  }
  const int N = grid_.intervals();
  std::vector<int> unknown(N, -1);
  for (int d = 0; d < D; ++d) {
    if (known[d]) continue;
    const int k = layout_.defects[d].interval;
    if (k < 0 || k >= N || unknown[k] >= 0) return NlpMultipliers();
    unknown[k] = d;
  }
  std::vector<int> start_block(N, -1);
  for (int j = 0; j < S; ++j) {
    const int k = layout_.states[j].interval_start;
    if (k >= 0 && k < N) start_block[k] = j;
  }
  std::vector<std::vector<int>> points_of_state(S);
  for (size_t e = 0; e < layout_.points.size(); ++e) {
    points_of_state[layout_.points[e].state].push_back(static_cast<int>(e));
  }
  std::vector<std::vector<const StateUse*>> uses_of_state(S);
  for (const auto& use : state_uses_) uses_of_state[use.state].push_back(&use);

  auto x_of = [&](int j) { return z.segment(layout_.states[j].offset, nx_); };
  auto u_of = [&](int i) { return z.segment(layout_.controls[i].offset, nu_); };
  Vec f(nx_), Lx(nx_), Lu(nu_), c(nc_);
  Mat fx(nx_, nx_), fu(nx_, nu_), cx(nc_, nx_), cu(nc_, nu_);
  double L;
  for (int k = 0; k < N; ++k) {
    const int j = start_block[k], u = unknown[k];
    if (j < 0 || u < 0) return NlpMultipliers();
    Mat M = Mat::Zero(nx_, nx_);
    Vec rhs = P.col(j);
    auto future = [&](int d) { return layout_.defects[d].interval >= k; };
    for (const StateUse* use : uses_of_state[j]) {
      if (!future(use->defect)) continue;
      if (use->defect == u) {
        M.diagonal().array() += use->coeff;
      } else {
        rhs -= use->coeff * lambda.segment(defect_row(use->defect), nx_);
      }
    }
    for (int e : points_of_state[j]) {
      const auto& p = layout_.points[e];
      ocp_.DynamicsJacobian(p.t, x_of(p.state), u_of(p.control), f, fx, fu);
      for (const auto& use : point_uses_[e]) {
        if (!future(use.defect)) continue;
        if (use.defect == u) {
          M += r * use.coeff * fx.transpose();
        } else {
          rhs -= r * use.coeff * fx.transpose() * lambda.segment(defect_row(use.defect), nx_);
        }
      }
      if (p.future_cost_weight != 0.0) {
        ocp_.RunningCostGradient(p.t, x_of(p.state), u_of(p.control), &L, Lx, Lu);
        rhs -= r * p.future_cost_weight * Lx;
      }
      if (path_point_row_[e] >= 0) {
        ocp_.PathConstraintsJacobian(p.t, x_of(p.state), u_of(p.control), c, cx, cu);
        rhs -= cx.transpose() * lambda.segment(path_point_row_[e], nc_);
      }
    }
    const Eigen::FullPivLU<Mat> lu(M);
    if (!lu.isInvertible()) return NlpMultipliers();
    lambda.segment(defect_row(u), nx_) = lu.solve(rhs);
  }

  // Back to the NLP's scaled units (Costates(): lambda = lambda_hat row_scale / objective_scale).
  NlpMultipliers out;
  out.lambda = lambda.cwiseQuotient(row_scale_) * objective_scale_;
  const Vec bound_scale = objective_scale_ * var_scale_;
  out.z_lower = z_lower.cwiseMax(0.0).cwiseProduct(bound_scale);
  out.z_upper = z_upper.cwiseMax(0.0).cwiseProduct(bound_scale);
  if (!out.Fits(n, num_constraints_)) return NlpMultipliers();
  return out;
}

}  // namespace ocpb
