// Time grids t0 = t_0 < t_1 < ... < t_N = tf.
#pragma once

#include <vector>

namespace ocpb {

/// A strictly increasing set of time points; interval k is [t_k, t_{k+1}], of length h(k).
class TimeGrid {
 public:
  TimeGrid() = default;
  /// N intervals of equal length. Throws std::invalid_argument unless N >= 1 and tf > t0.
  static TimeGrid Uniform(double t0, double tf, int intervals);
  /// Arbitrary points; throws std::invalid_argument unless strictly increasing, finite, >= 2.
  static TimeGrid FromPoints(std::vector<double> points);

  int intervals() const { return static_cast<int>(points_.size()) - 1; }
  int size() const { return static_cast<int>(points_.size()); }
  double t(int k) const { return points_[k]; }
  double h(int k) const { return points_[k + 1] - points_[k]; }
  double t0() const { return points_.front(); }
  double tf() const { return points_.back(); }
  bool uniform() const { return uniform_; }
  const std::vector<double>& points() const { return points_; }

  /// The interval k with t_k <= t < t_{k+1}; t at or past tf gives the last interval,
  /// t before t0 the first.
  int Locate(double t) const;
  /// Every interval split into `factor` equal pieces.
  TimeGrid Refined(int factor) const;
  /// Every `factor`-th node (the same points, so the kept nodes are exactly the originals; a
  /// uniform grid stays uniform). Throws std::invalid_argument unless factor >= 1 divides
  /// intervals().
  TimeGrid Coarsened(int factor) const;
  /// The same relative node positions on [t0, tf] (a free final time's grid at T = tf): t_k ->
  /// t0 + (t_k - t0) (tf - t0) / (tf() - t0), the last node exactly tf. Throws
  /// std::invalid_argument unless tf > t0 is finite.
  TimeGrid StretchedTo(double tf) const;

 private:
  std::vector<double> points_;
  bool uniform_ = false;
};

}  // namespace ocpb
