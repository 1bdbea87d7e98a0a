// s(q) precomputed on the workspace grid and interpolated smoothly.
#pragma once

#include <string>

#include <Eigen/Core>

#include "problems/channel/bicubic_spline.h"
#include "problems/channel/channel_parameters.h"
#include "problems/channel/channel_quality.h"
#include "problems/channel/grid_predictor.h"

namespace ocpb {

/// Which function of s the map interpolates.
enum class MapQuantity {
  /// g = ln s is interpolated and s = exp(g): positive everywhere, and ln s is much closer to
  /// a low-order polynomial than s (s spans about 5 decades over the paper's workspace), so
  /// the relative error is smaller (measured in problems/channel/README.md).
  kLogS,
  /// s itself.
  kS,
};
const char* ToString(MapQuantity quantity);
/// "log-s" or "s"; throws std::invalid_argument otherwise.
MapQuantity MapQuantityFromString(const std::string& name);

struct MapOptions {
  MapQuantity quantity = MapQuantity::kLogS;
};

/// A ChannelQuality from values of s at the points of a GridSpec, interpolated by a C2
/// not-a-knot bicubic spline (BicubicSpline): value, gradient and Hessian in about 30 ns.
/// With kLogS: s = exp(g), grad s = s grad g, Hess s = s (grad g grad g^T + Hess g).
///
/// Outside the grid points: between the outermost points and the workspace edge (half a cell)
/// the boundary cells' polynomials extrapolate; beyond the workspace rectangle q is clamped to
/// it, so s is continuous and its derivative across the violated edge is 0.
///
/// Which provider a problem uses (exact predictor or map) is recorded through Describe(),
/// e.g. "map bicubic log-s h=0.1m 500x500 of [gp-exact m=500 ...]".
class ChannelMap final : public ChannelQuality {
 public:
  /// `s` is grid.nx x grid.ny, finite and > 0. `source` describes where s came from.
  /// Throws std::invalid_argument otherwise.
  ChannelMap(const GridSpec& grid,
             const Eigen::MatrixXd& s,
             const MapOptions& options,
             std::string source);
  /// The map of a grid prediction of `predictor`.
  static ChannelMap FromPrediction(const GridPrediction& prediction,
                                   const GpChannelPredictor& predictor,
                                   const MapOptions& options = {});

  void Evaluate(const Eigen::Vector2d& q,
                double* s,
                Eigen::Vector2d* grad,
                Eigen::Matrix2d* hess) const override;
  std::string Describe() const override;

  const GridSpec& grid() const { return grid_; }
  const MapOptions& options() const { return options_; }

 private:
  GridSpec grid_;
  MapOptions options_;
  std::string source_;
  BicubicSpline spline_;
};

}  // namespace ocpb
