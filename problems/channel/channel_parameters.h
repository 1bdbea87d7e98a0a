// The statistical channel model of OCPBench and the workspace grid it lives on.
#pragma once

#include <string>

#include <Eigen/Core>

namespace ocpb {

/// Parameters of the channel model (Malmirchegini and Mostofi, IEEE TWC 2012; the paper's
/// Section II.B and IV):
///
///   Gamma_dB(q) = K_PL - 10 n_PL log10 max(|q - q_b|, d_floor) + SH(q) + MP(q),
///
/// the received power in dBm at q for a 0 dBm transmitter at the base station q_b. SH is zero-mean
/// Gaussian shadowing with E[SH(a) SH(b)] = xi^2 exp(-|a - b| / eta); MP is spatially
/// uncorrelated multipath whose dB-domain standard deviation the predictor takes to be rho
/// (Phi = Omega + rho^2 I). The same struct holds true values (simulation) and estimates
/// (prediction). Defaults are the paper's: K_PL = -41.34, n_PL = 3.86, xi = 3.20 dB,
/// eta = 3.09 m, rho = 1.64 dB, q_b = (5, 5).
///
/// The distance floor d_floor keeps log10 |q - q_b| finite at the base station. Inside the floor
/// the path-loss term is constant (its gradient and Hessian are 0); the kink lies on the circle
/// |q - q_b| = d_floor. The default 0.1 m is one grid step of the paper's grid, the floor the
/// companion simulator uses.
struct ChannelParameters {
  double k_pl = -41.34;  ///< K_PL: gain at 1 m, dB (finite)
  double n_pl = 3.86;    ///< n_PL: path-loss exponent (finite)
  double xi = 3.20;      ///< shadowing standard deviation, dB (> 0)
  double eta = 3.09;     ///< shadowing correlation distance, m (> 0)
  double rho = 1.64;     ///< multipath standard deviation in dB (> 0)
  Eigen::Vector2d base_station = Eigen::Vector2d(5.0, 5.0);  ///< q_b, m (finite)
  double distance_floor = 0.1;                               ///< d_floor, m (> 0)

  /// max(|q - q_b|, d_floor).
  double FlooredDistance(const Eigen::Vector2d& q) const;
  /// K_PL - 10 n_PL log10 max(|q - q_b|, d_floor), dB.
  double PathLossDb(const Eigen::Vector2d& q) const;
  /// The same with its gradient and Hessian in q (either may be null); both are 0 inside the
  /// floor. With e = q - q_b, d = |e|, u = e/d, c = 10 n_PL / ln 10:
  ///   grad = -c e / d^2,  Hess = -c (I - 2 u u^T) / d^2.
  double PathLossDb(const Eigen::Vector2d& q, Eigen::Vector2d* grad, Eigen::Matrix2d* hess) const;
  /// One-line reason in *error (may be null) when a field breaks its rule.
  bool IsValid(std::string* error) const;
};

/// A rectangular lattice of cell centres covering the workspace
/// [x_min, x_min + nx h] x [y_min, y_min + ny h]:
///   point(i, j) = (x_min + (i + 1/2) h, y_min + (j + 1/2) h),  0 <= i < nx, 0 <= j < ny.
/// Defaults: the paper's 50 m x 50 m workspace at h = 0.1 m, 500 x 500 = 250,000 points.
/// Fields on the grid are Eigen::MatrixXd of size nx x ny (entry (i, j) at point(i, j)); their
/// column-major storage is row-major [j][i], the layout of an image with y up.
struct GridSpec {
  double x_min = 0.0;       ///< m (finite)
  double y_min = 0.0;       ///< m (finite)
  double resolution = 0.1;  ///< h, m (> 0)
  int nx = 500;             ///< points along x (>= 4)
  int ny = 500;             ///< points along y (>= 4)

  /// The workspace width x height of `width_m` x `height_m` at `resolution` (rounded to whole
  /// cells); throws std::invalid_argument when that gives fewer than 4 cells per side.
  static GridSpec Workspace(
      double width_m, double height_m, double resolution, double x_min = 0.0, double y_min = 0.0);

  Eigen::Vector2d Point(int i, int j) const {
    return Eigen::Vector2d(x_min + (i + 0.5) * resolution, y_min + (j + 0.5) * resolution);
  }
  long num_points() const { return static_cast<long>(nx) * ny; }
  double x_max() const { return x_min + nx * resolution; }
  double y_max() const { return y_min + ny * resolution; }
  /// True when q lies in the covered rectangle [x_min, x_max] x [y_min, y_max] (edges included).
  bool Contains(const Eigen::Vector2d& q) const {
    return q.x() >= x_min && q.x() <= x_max() && q.y() >= y_min && q.y() <= y_max();
  }
  /// The cell containing q, clamped to the grid.
  void NearestCell(const Eigen::Vector2d& q, int* i, int* j) const;
  bool IsValid(std::string* error) const;
};

}  // namespace ocpb
