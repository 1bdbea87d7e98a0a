#include "problems/channel/gp_predictor.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "problems/channel/parameter_estimator.h"

namespace ocpb {
namespace {

std::string Pos(const Eigen::Vector2d& q) {
  std::ostringstream os;
  os << "(" << q.x() << ", " << q.y() << ")";
  return os.str();
}

std::string Num(double v) {  // shortest form (std::to_string prints 1e-9 as 0.000000)
  std::ostringstream os;
  os << v;
  return os.str();
}

}  // namespace

bool GpPredictorOptions::IsValid(std::string* error) const {
  if (!units.IsValid(error)) return false;
  if (!(coincidence_tolerance >= 0.0) || !std::isfinite(coincidence_tolerance)) {
    if (error != nullptr) *error = "coincidence_tolerance must be finite and >= 0";
    return false;
  }
  if (!(kink_radius >= 0.0) || !std::isfinite(kink_radius)) {
    if (error != nullptr) *error = "kink_radius must be finite and >= 0";
    return false;
  }
  return true;
}

GpChannelPredictor::GpChannelPredictor(const ChannelParameters& parameters,
                                       const MeasurementSet& measurements,
                                       const GpPredictorOptions& options)
    : parameters_(parameters), options_(options) {
  std::string error;
  if (!parameters.IsValid(&error)) throw std::invalid_argument("predictor parameters: " + error);
  if (!options.IsValid(&error)) throw std::invalid_argument("predictor options: " + error);
  ValidateMeasurements(measurements, parameters);
  xi2_ = parameters.xi * parameters.xi;
  rho2_ = parameters.rho * parameters.rho;
  positions_.resize(2, 0);
  bool changed = false;
  Append(measurements, &changed);
  if (num_measurements() < 3) {
    throw std::invalid_argument("need at least 3 distinct measurement positions, got " +
                                std::to_string(num_measurements()));
  }
  Factorize();
  UpdateAlpha();
}

void GpChannelPredictor::Append(const MeasurementSet& more, bool* changed_existing) {
  const int m0 = num_measurements();
  const int k = static_cast<int>(more.positions.size());
  const double tol = options_.coincidence_tolerance;
  positions_.conservativeResize(2, m0 + k);
  values_.conservativeResize(m0 + k);
  int m = m0;
  for (int n = 0; n < k; ++n) {
    const Eigen::Vector2d& q = more.positions[n];
    int twin = -1;
    for (int i = 0; i < m; ++i) {
      if ((positions_.col(i) - q).norm() <= tol) {
        twin = i;
        break;
      }
    }
    if (twin >= 0) {
      if (!options_.merge_coincident) {
        const std::string what = twin < m0 ? "existing measurement " + std::to_string(twin)
                                           : "new measurement " + std::to_string(twin - m0);
        throw std::invalid_argument("measurement " + std::to_string(n) + " at " + Pos(q) +
                                    " coincides with " + what + " (closer than " + Num(tol) +
                                    " m); remove repeats or set merge_coincident");
      }
      values_[twin] = (values_[twin] * counts_[twin] + more.values_db[n]) / (counts_[twin] + 1);
      ++counts_[twin];
      if (twin < m0) *changed_existing = true;
      continue;
    }
    positions_.col(m) = q;
    values_[m] = more.values_db[n];
    counts_.push_back(1);
    ++m;
  }
  positions_.conservativeResize(2, m);
  values_.conservativeResize(m);
}

void GpChannelPredictor::Reserve(int m, int keep) {
  if (factor_.rows() >= m) return;
  const Eigen::Index capacity = std::max<Eigen::Index>(m, 2 * factor_.rows());
  Eigen::MatrixXd grown(capacity, capacity);
  grown.topLeftCorner(keep, keep) = factor_.topLeftCorner(keep, keep);
  factor_.swap(grown);
}

void GpChannelPredictor::Factorize() {
  const int m = num_measurements();
  Eigen::MatrixXd phi(m, m);
  for (int j = 0; j < m; ++j) {
    for (int i = j; i < m; ++i) {
      phi(i, j) = Kernel((positions_.col(i) - positions_.col(j)).norm());
    }
    phi(j, j) += rho2_;
  }
  Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt(phi);
  if (llt.info() != Eigen::Success) {
    throw std::runtime_error(
        "predictor: Phi = Omega + rho^2 I is not numerically positive "
        "definite");
  }
  if (factor_.rows() < m) factor_.resize(m, m);
  factor_.topLeftCorner(m, m) = llt.matrixL();
  residual_solve_.resize(m);
  for (int i = 0; i < m; ++i) {
    residual_solve_[i] = values_[i] - PathLossMean(positions_.col(i), nullptr, nullptr);
  }
  cholesky_factor().triangularView<Eigen::Lower>().solveInPlace(residual_solve_);
}

void GpChannelPredictor::UpdateAlpha() {
  alpha_ = residual_solve_;
  cholesky_factor().transpose().triangularView<Eigen::Upper>().solveInPlace(alpha_);
}

void GpChannelPredictor::AddMeasurements(const MeasurementSet& more, UpdateMethod method) {
  if (more.values_db.size() != more.positions.size()) {
    throw std::invalid_argument("new measurements: " + std::to_string(more.positions.size()) +
                                " positions but " + std::to_string(more.values_db.size()) +
                                " values");
  }
  for (std::size_t n = 0; n < more.positions.size(); ++n) {
    const Eigen::Vector2d& q = more.positions[n];
    if (!q.allFinite() || !std::isfinite(more.values_db[n])) {
      throw std::invalid_argument("new measurement " + std::to_string(n) +
                                  " has a non-finite position or value");
    }
    if ((q - parameters_.base_station).norm() < parameters_.distance_floor) {
      throw std::invalid_argument("new measurement " + std::to_string(n) + " at " + Pos(q) +
                                  " lies within the distance floor of the base station");
    }
  }
  // Work on copies so that a rejected batch leaves the predictor unchanged.
  const Eigen::Matrix2Xd old_positions = positions_;
  const Eigen::VectorXd old_values = values_;
  const std::vector<int> old_counts = counts_;
  const int m0 = num_measurements();
  bool changed = false;
  try {
    Append(more, &changed);
  } catch (...) {
    positions_ = old_positions;
    values_ = old_values;
    counts_ = old_counts;
    throw;
  }
  const int m1 = num_measurements();
  if (changed || (m1 > m0 && method == UpdateMethod::kRefactorize)) {
    // A merged value changed Y at an existing position, or a full refactorization was asked.
    Factorize();
  } else if (m1 > m0) {
    {  // bordered update
      const int k = m1 - m0;
      Eigen::MatrixXd b(m0, k), s(k, k);
      for (int c = 0; c < k; ++c) {
        for (int i = 0; i < m0; ++i) {
          b(i, c) = Kernel((positions_.col(i) - positions_.col(m0 + c)).norm());
        }
        for (int r = c; r < k; ++r) {
          s(r, c) = Kernel((positions_.col(m0 + r) - positions_.col(m0 + c)).norm());
        }
        s(c, c) += rho2_;
      }
      const auto L0 = factor_.topLeftCorner(m0, m0);
      if (k == 1) {  // the vector solve avoids the matrix solver's packing of L (O(m^2) copy)
        Eigen::VectorXd col = b.col(0);
        L0.triangularView<Eigen::Lower>().solveInPlace(col);
        b.col(0) = col;
      } else {
        L0.triangularView<Eigen::Lower>().solveInPlace(b);  // B = L^{-1} Phi_12
      }
      s.triangularView<Eigen::Lower>() -= b.transpose() * b;  // Phi_22 - B^T B
      Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt(s);
      if (llt.info() != Eigen::Success) {
        positions_ = old_positions;
        values_ = old_values;
        counts_ = old_counts;
        throw std::runtime_error(
            "predictor: the bordered Cholesky update lost positive "
            "definiteness");
      }
      // The rows of L, and so the entries of L^{-1} r, above the new ones do not change:
      // z_new = L_22^{-1} (r_new - B^T z_old).
      Eigen::VectorXd z_new(k);
      for (int c = 0; c < k; ++c) {
        z_new[c] = values_[m0 + c] - PathLossMean(positions_.col(m0 + c), nullptr, nullptr);
      }
      z_new -= b.transpose() * residual_solve_;
      llt.matrixL().solveInPlace(z_new);
      Reserve(m1, m0);
      factor_.block(0, m0, m0, k).setZero();
      factor_.block(m0, 0, k, m0) = b.transpose();
      factor_.block(m0, m0, k, k) = llt.matrixL();
      residual_solve_.conservativeResize(m1);
      residual_solve_.tail(k) = z_new;
    }
  }
  if (m1 > m0 || changed) UpdateAlpha();
}

double GpChannelPredictor::PathLossMean(const Eigen::Vector2d& q,
                                        Eigen::Vector2d* grad,
                                        Eigen::Matrix2d* hess) const {
  return parameters_.PathLossDb(q, grad, hess);
}

void GpChannelPredictor::Predict(const Eigen::Vector2d& q, int order, PointPrediction* out) const {
  const int m = num_measurements();
  const double inv_eta = 1.0 / parameters_.eta;
  Eigen::VectorXd psi(m);
  Eigen::MatrixXd dpsi;   // m x 2
  Eigen::MatrixXd d2psi;  // m x 3: xx, xy, yy
  if (order >= 1) dpsi.resize(m, 2);
  if (order >= 2) d2psi.resize(m, 3);
  for (int i = 0; i < m; ++i) {
    const double ex = q.x() - positions_(0, i), ey = q.y() - positions_(1, i);
    const double d = std::sqrt(ex * ex + ey * ey);
    const double k = xi2_ * std::exp(-d * inv_eta);
    psi[i] = k;
    if (order < 1) continue;
    if (d <= options_.kink_radius) {
      dpsi.row(i).setZero();
      if (order >= 2) d2psi.row(i).setZero();
      continue;
    }
    const double ux = ex / d, uy = ey / d;
    dpsi(i, 0) = -k * inv_eta * ux;
    dpsi(i, 1) = -k * inv_eta * uy;
    if (order >= 2) {
      const double a = k * inv_eta * inv_eta, c = k * inv_eta / d;
      d2psi(i, 0) = a * ux * ux - c * (1.0 - ux * ux);
      d2psi(i, 1) = a * ux * uy + c * ux * uy;
      d2psi(i, 2) = a * uy * uy - c * (1.0 - uy * uy);
    }
  }
  Eigen::Vector2d pl_grad;
  Eigen::Matrix2d pl_hess;
  out->mean_db = PathLossMean(q, order >= 1 ? &pl_grad : nullptr, order >= 2 ? &pl_hess : nullptr) +
                 psi.dot(alpha_);
  const auto L = cholesky_factor().triangularView<Eigen::Lower>();
  Eigen::VectorXd w = L.solve(psi);
  out->variance_db2 = PriorVariance() - w.squaredNorm();
  if (order < 1) return;
  out->mean_grad = pl_grad + dpsi.transpose() * alpha_;
  cholesky_factor().transpose().triangularView<Eigen::Upper>().solveInPlace(w);  // Phi^{-1} Psi
  out->variance_grad = -2.0 * dpsi.transpose() * w;
  if (order < 2) return;
  const Eigen::Vector3d ha = d2psi.transpose() * alpha_;
  const Eigen::Vector3d hv = d2psi.transpose() * w;
  out->mean_hess = pl_hess;
  out->mean_hess(0, 0) += ha[0];
  out->mean_hess(0, 1) += ha[1];
  out->mean_hess(1, 0) += ha[1];
  out->mean_hess(1, 1) += ha[2];
  const Eigen::MatrixXd wj = L.solve(dpsi);  // L^{-1} dPsi
  Eigen::Matrix2d gram = wj.transpose() * wj;
  gram(0, 0) += hv[0];
  gram(0, 1) += hv[1];
  gram(1, 0) += hv[1];
  gram(1, 1) += hv[2];
  out->variance_hess = -2.0 * gram;
}

double GpChannelPredictor::Mean(const Eigen::Vector2d& q) const {
  PointPrediction p;
  Predict(q, 0, &p);
  return p.mean_db;
}

double GpChannelPredictor::Variance(const Eigen::Vector2d& q) const {
  PointPrediction p;
  Predict(q, 0, &p);
  return p.variance_db2;
}

void GpChannelPredictor::Evaluate(const Eigen::Vector2d& q,
                                  double* s,
                                  Eigen::Vector2d* grad,
                                  Eigen::Matrix2d* hess) const {
  PointPrediction p;
  Predict(q, hess != nullptr ? 2 : (grad != nullptr ? 1 : 0), &p);
  ComposeInverseCnr(p.mean_db,
                    p.mean_grad,
                    p.mean_hess,
                    p.variance_db2,
                    p.variance_grad,
                    p.variance_hess,
                    options_.units,
                    s,
                    grad,
                    hess);
}

std::string GpChannelPredictor::Describe() const {
  std::ostringstream os;
  os << "gp-exact m=" << num_measurements() << " K_PL=" << parameters_.k_pl
     << " n_PL=" << parameters_.n_pl << " xi=" << parameters_.xi << " eta=" << parameters_.eta
     << " rho=" << parameters_.rho;
  return os.str();
}

}  // namespace ocpb
