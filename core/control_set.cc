#include "core/control_set.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ocpb {

ControlSet ControlSet::Unbounded(int n) {
  const double inf = std::numeric_limits<double>::infinity();
  ControlSet set;
  if (n > 0) set.AddBox(Vec::Constant(n, -inf), Vec::Constant(n, inf));
  return set;
}

ControlSet ControlSet::Box(const Vec& lower, const Vec& upper) {
  ControlSet set;
  set.AddBox(lower, upper);
  return set;
}

ControlSet& ControlSet::AddBox(const Vec& lower, const Vec& upper) {
  if (lower.size() != upper.size() || lower.size() == 0) {
    throw std::invalid_argument("ControlSet::AddBox: lower and upper must have the same positive size");
  }
  for (int i = 0; i < lower.size(); ++i) {
    if (std::isnan(lower[i]) || std::isnan(upper[i]) || lower[i] > upper[i]) {
      throw std::invalid_argument("ControlSet::AddBox: need lower <= upper, no NaN");
    }
  }
  Block b;
  b.kind = Kind::kBox;
  b.offset = dimension_;
  b.size = static_cast<int>(lower.size());
  b.lower = lower;
  b.upper = upper;
  blocks_.push_back(b);
  dimension_ += b.size;
  return *this;
}

ControlSet& ControlSet::AddBall(int size, double radius) { return AddBall(Vec::Zero(size), radius); }

ControlSet& ControlSet::AddBall(const Vec& center, double radius) {
  if (center.size() == 0 || !(radius > 0.0) || !std::isfinite(radius)) {
    throw std::invalid_argument("ControlSet::AddBall: need a positive finite radius and size >= 1");
  }
  Block b;
  b.kind = Kind::kBall;
  b.offset = dimension_;
  b.size = static_cast<int>(center.size());
  b.center = center;
  b.radius = radius;
  blocks_.push_back(b);
  dimension_ += b.size;
  return *this;
}

bool ControlSet::IsBox() const {
  return std::all_of(blocks_.begin(), blocks_.end(), [](const Block& b) { return b.kind == Kind::kBox; });
}

void ControlSet::BoundingBox(Vec* lower, Vec* upper) const {
  lower->resize(dimension_);
  upper->resize(dimension_);
  for (const Block& b : blocks_) {
    if (b.kind == Kind::kBox) {
      lower->segment(b.offset, b.size) = b.lower;
      upper->segment(b.offset, b.size) = b.upper;
    } else {
      lower->segment(b.offset, b.size) = b.center.array() - b.radius;
      upper->segment(b.offset, b.size) = b.center.array() + b.radius;
    }
  }
}

void ControlSet::Project(VecRef u) const {
  for (const Block& b : blocks_) {
    auto v = u.segment(b.offset, b.size);
    if (b.kind == Kind::kBox) {
      v = v.cwiseMax(b.lower).cwiseMin(b.upper);
    } else {
      const double r = (v - b.center).norm();
      if (r > b.radius) v = b.center + (b.radius / r) * (v - b.center);
    }
  }
}

double ControlSet::Violation(ConstVecRef u) const {
  if (!u.allFinite()) return std::numeric_limits<double>::infinity();
  double worst = 0.0;
  for (const Block& b : blocks_) {
    const auto v = u.segment(b.offset, b.size);
    if (b.kind == Kind::kBox) {
      worst = std::max(worst, (b.lower - v).maxCoeff());
      worst = std::max(worst, (v - b.upper).maxCoeff());
    } else {
      worst = std::max(worst, (v - b.center).norm() - b.radius);
    }
  }
  return worst;
}

}  // namespace ocpb
