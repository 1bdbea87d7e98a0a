#include "problems/channel/channel_map.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace ocpb {

const char* ToString(MapQuantity quantity) {
  return quantity == MapQuantity::kLogS ? "log-s" : "s";
}

MapQuantity MapQuantityFromString(const std::string& name) {
  if (name == "log-s") return MapQuantity::kLogS;
  if (name == "s") return MapQuantity::kS;
  throw std::invalid_argument("unknown map quantity '" + name + "' (valid: log-s, s)");
}

ChannelMap::ChannelMap(const GridSpec& grid,
                       const Eigen::MatrixXd& s,
                       const MapOptions& options,
                       std::string source)
    : grid_(grid), options_(options), source_(std::move(source)) {
  std::string error;
  if (!grid.IsValid(&error)) throw std::invalid_argument("channel map: " + error);
  if (s.rows() != grid.nx || s.cols() != grid.ny) {
    throw std::invalid_argument("channel map: values must be nx x ny of the grid");
  }
  if (!s.allFinite() || !(s.minCoeff() > 0.0)) {
    throw std::invalid_argument("channel map: s must be finite and > 0 at every grid point");
  }
  const Eigen::Vector2d p0 = grid.Point(0, 0);
  if (options.quantity == MapQuantity::kLogS) {
    spline_ = BicubicSpline(p0.x(), p0.y(), grid.resolution, s.array().log().matrix());
  } else {
    spline_ = BicubicSpline(p0.x(), p0.y(), grid.resolution, s);
  }
}

ChannelMap ChannelMap::FromPrediction(const GridPrediction& prediction,
                                      const GpChannelPredictor& predictor,
                                      const MapOptions& options) {
  return ChannelMap(
      prediction.grid, prediction.s, options, predictor.Describe() + "; grid " + prediction.method);
}

void ChannelMap::Evaluate(const Eigen::Vector2d& q,
                          double* s,
                          Eigen::Vector2d* grad,
                          Eigen::Matrix2d* hess) const {
  const double x = std::clamp(q.x(), grid_.x_min, grid_.x_max());
  const double y = std::clamp(q.y(), grid_.y_min, grid_.y_max());
  const bool free_x = x == q.x(), free_y = y == q.y();
  double g;
  Eigen::Vector2d dg;
  Eigen::Matrix2d ddg;
  spline_.Evaluate(x,
                   y,
                   &g,
                   (grad != nullptr || hess != nullptr) ? &dg : nullptr,
                   hess != nullptr ? &ddg : nullptr);
  if (grad != nullptr || hess != nullptr) {
    if (!free_x) {
      dg[0] = 0.0;
      if (hess != nullptr) {
        ddg.row(0).setZero();
        ddg.col(0).setZero();
      }
    }
    if (!free_y) {
      dg[1] = 0.0;
      if (hess != nullptr) {
        ddg.row(1).setZero();
        ddg.col(1).setZero();
      }
    }
  }
  if (options_.quantity == MapQuantity::kS) {
    if (s != nullptr) *s = g;
    if (grad != nullptr) *grad = dg;
    if (hess != nullptr) *hess = ddg;
    return;
  }
  const double value = std::exp(g);
  if (s != nullptr) *s = value;
  if (grad != nullptr) *grad = value * dg;
  if (hess != nullptr) *hess = value * (dg * dg.transpose() + ddg);
}

std::string ChannelMap::Describe() const {
  std::ostringstream os;
  os << "map bicubic " << ToString(options_.quantity) << " h=" << grid_.resolution << "m "
     << grid_.nx << "x" << grid_.ny << " of [" << source_ << "]";
  return os.str();
}

}  // namespace ocpb
