#include "core/control_trajectory.h"

#include <algorithm>
#include <stdexcept>

namespace ocpb {

ControlTrajectory ControlTrajectory::PiecewiseConstant(const TimeGrid& grid, const Mat& values) {
  if (values.cols() != grid.intervals() || values.rows() < 1) {
    throw std::invalid_argument("piecewise-constant control: need nu x N values for N intervals");
  }
  ControlTrajectory c;
  c.interpolation_ = Interpolation::kPiecewiseConstant;
  c.nu_ = static_cast<int>(values.rows());
  c.grid_ = grid;
  c.values_ = values;
  return c;
}

ControlTrajectory ControlTrajectory::PiecewiseLinear(const TimeGrid& grid, const Mat& values) {
  if (values.cols() != grid.size() || values.rows() < 1) {
    throw std::invalid_argument("piecewise-linear control: need nu x (N+1) values for N intervals");
  }
  ControlTrajectory c;
  c.interpolation_ = Interpolation::kPiecewiseLinear;
  c.nu_ = static_cast<int>(values.rows());
  c.grid_ = grid;
  c.values_ = values;
  return c;
}

ControlTrajectory ControlTrajectory::Custom(int nu, const TimeGrid& grid, Function fn,
                                            std::string description) {
  if (nu < 1 || !fn) throw std::invalid_argument("custom control: need nu >= 1 and a function");
  ControlTrajectory c;
  c.interpolation_ = Interpolation::kCustom;
  c.nu_ = nu;
  c.grid_ = grid;
  c.function_ = std::move(fn);
  c.description_ = std::move(description);
  return c;
}

ControlTrajectory ControlTrajectory::Constant(const TimeGrid& grid, const Vec& value) {
  return PiecewiseConstant(grid, value.replicate(1, grid.intervals()));
}

const char* ControlTrajectory::InterpolationName() const {
  switch (interpolation_) {
    case Interpolation::kPiecewiseConstant:
      return "piecewise-constant";
    case Interpolation::kPiecewiseLinear:
      return "piecewise-linear";
    case Interpolation::kCustom:
      return "custom";
  }
  return "?";
}

void ControlTrajectory::Evaluate(double t, Side side, VecRef u) const {
  switch (interpolation_) {
    case Interpolation::kPiecewiseConstant: {
      int k = grid_.Locate(t);
      // Left limit at a breakpoint t_k (k > 0) belongs to the previous interval.
      if (side == Side::kLeft && k > 0 && t <= grid_.t(k)) --k;
      u = values_.col(k);
      return;
    }
    case Interpolation::kPiecewiseLinear: {
      const int k = grid_.Locate(t);
      const double s = std::clamp((t - grid_.t(k)) / grid_.h(k), 0.0, 1.0);
      u = (1.0 - s) * values_.col(k) + s * values_.col(k + 1);
      return;
    }
    case Interpolation::kCustom:
      function_(t, side, u);
      return;
  }
}

Vec ControlTrajectory::operator()(double t, Side side) const {
  Vec u(nu_);
  Evaluate(t, side, u);
  return u;
}

Mat ControlTrajectory::SampleIntervals(const TimeGrid& grid) const {
  Mat out(nu_, grid.intervals());
  for (int k = 0; k < grid.intervals(); ++k) {
    Evaluate(grid.t(k), Side::kRight, out.col(k));
  }
  return out;
}

}  // namespace ocpb
