// A control trajectory u(t) on [t0, tf] with the rule that interpolates it.
#pragma once

#include <functional>
#include <string>

#include "core/time_grid.h"
#include "core/types.h"

namespace ocpb {

/// Every method hands its controls to the common evaluator as one of these:
///  - piecewise constant: values (nu x N), u(t) = u_k on [t_k, t_{k+1});
///  - piecewise linear:   values (nu x N+1), linear between node values;
///  - custom: a method's own polynomial (for example collocation's), through a function.
/// At a breakpoint a one-sided limit is taken: `Side::kRight` gives u(t+), `kLeft` gives u(t-).
/// An integrator step on [a, b] evaluates u(a+) ... u(b-), so piecewise-constant controls
/// never mix two intervals inside one step.
class ControlTrajectory {
 public:
  enum class Interpolation { kPiecewiseConstant, kPiecewiseLinear, kCustom };
  enum class Side { kRight, kLeft };
  using Function = std::function<void(double t, Side side, VecRef u)>;

  ControlTrajectory() = default;
  static ControlTrajectory PiecewiseConstant(const TimeGrid& grid, const Mat& values);
  static ControlTrajectory PiecewiseLinear(const TimeGrid& grid, const Mat& values);
  static ControlTrajectory Custom(int nu, const TimeGrid& grid, Function fn, std::string description);
  /// A constant control on the grid (piecewise constant).
  static ControlTrajectory Constant(const TimeGrid& grid, const Vec& value);

  int nu() const { return nu_; }
  Interpolation interpolation() const { return interpolation_; }
  const TimeGrid& grid() const { return grid_; }
  /// The samples (empty for custom controls).
  const Mat& values() const { return values_; }
  const char* InterpolationName() const;

  void Evaluate(double t, Side side, VecRef u) const;
  Vec operator()(double t, Side side = Side::kRight) const;
  /// Samples this control as piecewise constant on `grid` (value at each interval's left end,
  /// from the right).
  Mat SampleIntervals(const TimeGrid& grid) const;

 private:
  Interpolation interpolation_ = Interpolation::kPiecewiseConstant;
  int nu_ = 0;
  TimeGrid grid_;
  Mat values_;
  Function function_;
  std::string description_;
};

}  // namespace ocpb
