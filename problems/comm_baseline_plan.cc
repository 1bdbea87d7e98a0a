#include "problems/comm_baseline_plan.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "problems/comm_fixed_path.h"
#include "problems/comm_path2d.h"

namespace ocpb {

std::optional<std::vector<double>> BaselineAccelerations(
    double length, double h, int N, double umax, std::string* why_not) {
  std::vector<double> u(static_cast<size_t>(std::max(N, 0)), 0.0);
  if (length == 0.0) return u;
  for (int m = 1; 2 * m <= N; ++m) {
    const double a = length / (h * h * m * static_cast<double>(N - m));
    if (a > umax) continue;
    for (int k = 0; k < m; ++k) {
      u[k] = a;
      u[N - 1 - k] = -a;
    }
    return u;
  }
  if (why_not) {
    std::ostringstream os;
    os << "baseline plan: " << length << " m cannot be covered in " << N << " steps of " << h
       << " s from rest to rest with |u| <= " << umax;
    *why_not = os.str();
  }
  return std::nullopt;
}

std::optional<double> BaselineRate(
    double bits, double sent, double t0, double tf, double rmax, std::string* why_not) {
  const double rate = (bits - sent) / (tf - t0);
  if (rate >= 0.0 && rate <= rmax) return rate;
  if (why_not) {
    std::ostringstream os;
    os << "baseline plan: sending " << bits - sent << " bits/Hz in " << tf - t0
       << " s needs a constant rate " << rate << ", outside [0, Rmax = " << rmax << "]";
    *why_not = os.str();
  }
  return std::nullopt;
}

// ---- the problems' BaselinePlan (declared in their headers) -----------------------------------

namespace {

// The grid checks both problems share: uniform, spanning the problem's horizon.
bool BaselineGridFits(const Ocp& ocp, const TimeGrid& grid, std::string* why_not) {
  const double scale = std::max(1.0, std::abs(ocp.tf()));
  if (!grid.uniform() || std::abs(grid.t0() - ocp.t0()) > 1e-9 * scale ||
      std::abs(grid.tf() - ocp.tf()) > 1e-9 * scale) {
    if (why_not) {
      *why_not = "baseline plan: needs a uniform grid on the problem's horizon [t0, tf]";
    }
    return false;
  }
  return true;
}

}  // namespace

std::optional<ControlTrajectory> CommPath2d::BaselinePlan(const TimeGrid& grid,
                                                          std::string* why_not) const {
  if (!BaselineGridFits(*this, grid, why_not)) return std::nullopt;
  if (options_.v0.squaredNorm() != 0.0) {
    if (why_not) *why_not = "baseline plan: defined from rest (v0 = 0)";
    return std::nullopt;
  }
  const int N = grid.intervals();
  const Eigen::Vector2d chord = options_.destination - options_.start;
  const double length = chord.norm();
  const std::optional<std::vector<double>> acc =
      BaselineAccelerations(length, grid.h(0), N, options_.umax, why_not);
  if (!acc) return std::nullopt;  // (its reason kept: the rate's check would overwrite it)
  const std::optional<double> rate = BaselineRate(
      options_.bits, options_.bits_sent, options_.t0, options_.tf, options_.rmax, why_not);
  if (!acc || !rate) return std::nullopt;
  const Eigen::Vector2d direction =
      length > 0.0 ? Eigen::Vector2d(chord / length) : Eigen::Vector2d::Zero();
  Mat U(3, N);
  for (int k = 0; k < N; ++k) {
    U.col(k) << (*acc)[k] * direction, *rate;
  }
  return ControlTrajectory::PiecewiseConstant(grid, U);
}

std::optional<ControlTrajectory> CommFixedPath::BaselinePlan(const TimeGrid& grid,
                                                             std::string* why_not) const {
  if (!BaselineGridFits(*this, grid, why_not)) return std::nullopt;
  const int N = grid.intervals();
  const std::optional<std::vector<double>> acc =
      BaselineAccelerations(path_->length(), grid.h(0), N, options_.umax, why_not);
  if (!acc) return std::nullopt;  // (its reason kept: the rate's check would overwrite it)
  const std::optional<double> rate =
      BaselineRate(options_.bits, 0.0, 0.0, options_.tf, options_.rmax, why_not);
  if (!acc || !rate) return std::nullopt;
  Mat U(2, N);
  for (int k = 0; k < N; ++k) U.col(k) << (*acc)[k], *rate;
  return ControlTrajectory::PiecewiseConstant(grid, U);
}

}  // namespace ocpb
