#include "problems/channel/channel_parameters.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/invalid.h"

namespace ocpb {

double ChannelParameters::FlooredDistance(const Eigen::Vector2d& q) const {
  return std::max((q - base_station).norm(), distance_floor);
}

double ChannelParameters::PathLossDb(const Eigen::Vector2d& q) const {
  return k_pl - 10.0 * n_pl * std::log10(FlooredDistance(q));
}

double ChannelParameters::PathLossDb(const Eigen::Vector2d& q,
                                     Eigen::Vector2d* grad,
                                     Eigen::Matrix2d* hess) const {
  constexpr double kTenOverLn10 = 4.3429448190325175;  // 10 / ln 10
  const Eigen::Vector2d e = q - base_station;
  const double d = e.norm();
  const bool inside = !(d > distance_floor);
  const double value = k_pl - 10.0 * n_pl * std::log10(inside ? distance_floor : d);
  if (grad != nullptr) {
    *grad = inside ? Eigen::Vector2d::Zero() : Eigen::Vector2d(-kTenOverLn10 * n_pl / (d * d) * e);
  }
  if (hess != nullptr) {
    if (inside) {
      hess->setZero();
    } else {
      const Eigen::Vector2d u = e / d;
      *hess =
          -kTenOverLn10 * n_pl / (d * d) * (Eigen::Matrix2d::Identity() - 2.0 * u * u.transpose());
    }
  }
  return value;
}

bool ChannelParameters::IsValid(std::string* error) const {
  if (!std::isfinite(k_pl)) return Invalid(error, "K_PL must be finite");
  if (!std::isfinite(n_pl)) return Invalid(error, "n_PL must be finite");
  if (!(xi > 0.0) || !std::isfinite(xi)) return Invalid(error, "xi must be finite and > 0 (dB)");
  if (!(eta > 0.0) || !std::isfinite(eta)) return Invalid(error, "eta must be finite and > 0 (m)");
  if (!(rho > 0.0) || !std::isfinite(rho)) return Invalid(error, "rho must be finite and > 0 (dB)");
  if (!base_station.allFinite()) return Invalid(error, "base station position must be finite");
  if (!(distance_floor > 0.0) || !std::isfinite(distance_floor)) {
    return Invalid(error, "distance floor must be finite and > 0 (m)");
  }
  return true;
}

GridSpec GridSpec::Workspace(
    double width_m, double height_m, double resolution, double x_min, double y_min) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw std::invalid_argument("workspace resolution must be finite and > 0 m");
  }
  if (!std::isfinite(width_m) || !std::isfinite(height_m)) {
    throw std::invalid_argument("workspace size must be finite");
  }
  const double cx = std::round(width_m / resolution);
  const double cy = std::round(height_m / resolution);
  if (!(cx >= 4.0) || !(cy >= 4.0) || cx > 1e5 || cy > 1e5) {
    throw std::invalid_argument(
        "workspace must have between 4 and 100000 cells per side at the "
        "given resolution");
  }
  GridSpec g;
  g.x_min = x_min;
  g.y_min = y_min;
  g.resolution = resolution;
  g.nx = static_cast<int>(cx);
  g.ny = static_cast<int>(cy);
  return g;
}

void GridSpec::NearestCell(const Eigen::Vector2d& q, int* i, int* j) const {
  const double fi = std::floor((q.x() - x_min) / resolution);
  const double fj = std::floor((q.y() - y_min) / resolution);
  *i = static_cast<int>(std::clamp(fi, 0.0, static_cast<double>(nx - 1)));
  *j = static_cast<int>(std::clamp(fj, 0.0, static_cast<double>(ny - 1)));
}

bool GridSpec::IsValid(std::string* error) const {
  if (!std::isfinite(x_min) || !std::isfinite(y_min)) {
    return Invalid(error, "grid origin must be finite");
  }
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    return Invalid(error, "grid resolution must be finite and > 0 m");
  }
  if (nx < 4 || ny < 4) return Invalid(error, "grid needs at least 4 points per side");
  return true;
}

}  // namespace ocpb
