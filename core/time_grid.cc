#include "core/time_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace ocpb {

TimeGrid TimeGrid::Uniform(double t0, double tf, int intervals) {
  if (intervals < 1) throw std::invalid_argument("time grid: need N >= 1 intervals");
  if (!std::isfinite(t0) || !std::isfinite(tf) || !(tf > t0)) {
    throw std::invalid_argument("time grid: need finite t0 < tf");
  }
  TimeGrid g;
  g.points_.resize(intervals + 1);
  const double h = (tf - t0) / intervals;
  for (int k = 0; k <= intervals; ++k) g.points_[k] = t0 + k * h;
  g.points_.back() = tf;
  g.uniform_ = true;
  return g;
}

TimeGrid TimeGrid::FromPoints(std::vector<double> points) {
  if (points.size() < 2) throw std::invalid_argument("time grid: need at least 2 points");
  for (size_t k = 0; k < points.size(); ++k) {
    if (!std::isfinite(points[k])) throw std::invalid_argument("time grid: points must be finite");
    if (k > 0 && !(points[k] > points[k - 1])) {
      throw std::invalid_argument("time grid: points must be strictly increasing");
    }
  }
  TimeGrid g;
  g.points_ = std::move(points);
  g.uniform_ = false;
  return g;
}

int TimeGrid::Locate(double t) const {
  const auto it = std::upper_bound(points_.begin(), points_.end(), t);
  const int k = static_cast<int>(it - points_.begin()) - 1;
  return std::clamp(k, 0, intervals() - 1);
}

TimeGrid TimeGrid::StretchedTo(double tf) const {
  if (!std::isfinite(tf) || !(tf > t0())) {
    throw std::invalid_argument("time grid: a stretched grid needs a finite tf > t0");
  }
  const double r = (tf - t0()) / (this->tf() - t0());
  std::vector<double> pts = points_;
  for (double& p : pts) p = t0() + r * (p - t0());
  pts.back() = tf;
  TimeGrid g = FromPoints(std::move(pts));
  g.uniform_ = uniform_;
  return g;
}

TimeGrid TimeGrid::Coarsened(int factor) const {
  if (factor < 1 || intervals() % factor != 0) {
    throw std::invalid_argument("time grid: a coarsening factor must be >= 1 and divide the " +
                                std::to_string(intervals()) + " intervals (got " +
                                std::to_string(factor) + ")");
  }
  std::vector<double> pts;
  pts.reserve(intervals() / factor + 1);
  for (int k = 0; k <= intervals(); k += factor) pts.push_back(points_[k]);
  TimeGrid g = FromPoints(std::move(pts));
  g.uniform_ = uniform_;
  return g;
}

TimeGrid TimeGrid::Refined(int factor) const {
  if (factor < 1) throw std::invalid_argument("time grid: refinement factor must be >= 1");
  std::vector<double> pts;
  pts.reserve(intervals() * factor + 1);
  for (int k = 0; k < intervals(); ++k) {
    for (int j = 0; j < factor; ++j) pts.push_back(t(k) + h(k) * j / factor);
  }
  pts.push_back(tf());
  TimeGrid g = FromPoints(std::move(pts));
  g.uniform_ = uniform_;
  return g;
}

}  // namespace ocpb
