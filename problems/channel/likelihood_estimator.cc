#include "problems/channel/likelihood_estimator.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <nlopt.hpp>

namespace ocpb {

double ProfiledNeg2LogLikelihood(const Eigen::MatrixXd& distances,
                                 const Eigen::VectorXd& x,
                                 const Eigen::VectorXd& y,
                                 double eta,
                                 double nugget,
                                 bool restricted,
                                 LikelihoodFit* fit) {
  const Eigen::Index m = y.size();
  constexpr int p = 2;
  // R's lower triangle (the factorization reads only that).
  Eigen::MatrixXd R(m, m);
  const double shadow = 1.0 - nugget, inv_eta = 1.0 / eta;
  for (Eigen::Index j = 0; j < m; ++j) {
    R(j, j) = 1.0;
    for (Eigen::Index i = j + 1; i < m; ++i)
      R(i, j) = shadow * std::exp(-distances(i, j) * inv_eta);
  }
  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>, Eigen::Lower> llt(R);
  if (llt.info() != Eigen::Success) return HUGE_VAL;
  double log_det_r = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) log_det_r += 2.0 * std::log(R(i, i));

  // Whitened [H | y]: beta is ordinary least squares of the whitened system (by QR, which
  // also gives log det(H^T R^-1 H) for REML).
  Eigen::MatrixXd a(m, p + 1);
  a.col(0).setOnes();
  a.col(1) = x;
  a.col(2) = y;
  llt.matrixL().solveInPlace(a);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(a.leftCols(p));
  const Eigen::Vector2d beta = qr.solve(a.col(p));
  const double q = (a.col(p) - a.leftCols(p) * beta).squaredNorm();
  const double dof = static_cast<double>(restricted ? m - p : m);
  if (!(q > 0.0) || !std::isfinite(q)) return HUGE_VAL;
  const double sigma2 = q / dof;
  double n2ll = dof * (1.0 + std::log(2.0 * std::numbers::pi * sigma2)) + log_det_r;
  if (restricted) {
    for (int i = 0; i < p; ++i) n2ll += 2.0 * std::log(std::abs(qr.matrixQR()(i, i)));
  }
  if (fit != nullptr) {
    fit->k_pl = beta[0];
    fit->n_pl = beta[1];
    fit->sigma2 = sigma2;
    fit->eta = eta;
    fit->nugget = nugget;
    fit->neg2_log_likelihood = n2ll;
  }
  return std::isfinite(n2ll) ? n2ll : HUGE_VAL;
}

namespace {

struct Objective {
  const Eigen::MatrixXd* distances = nullptr;
  const Eigen::VectorXd* x = nullptr;
  const Eigen::VectorXd* y = nullptr;
  bool restricted = false;
  int evaluations = 0;
  double best = HUGE_VAL;
  std::vector<double> best_point;
};

double Evaluate(const std::vector<double>& z, std::vector<double>& /*grad*/, void* data) {
  auto* o = static_cast<Objective*>(data);
  ++o->evaluations;
  const double v = ProfiledNeg2LogLikelihood(
      *o->distances, *o->x, *o->y, std::exp(z[0]), std::exp(z[1]), o->restricted);
  if (v < o->best) {
    o->best = v;
    o->best_point = z;
  }
  // BOBYQA needs finite values; a failed factorization is far worse than any real point.
  return std::isfinite(v) ? v : 1e300;
}

}  // namespace

LikelihoodFit FitLikelihood(const Eigen::MatrixXd& distances,
                            const Eigen::VectorXd& x,
                            const Eigen::VectorXd& y,
                            double eta0,
                            double nugget0,
                            const LikelihoodFitOptions& options) {
  const std::vector<double> lo = {std::log(options.eta_min), std::log(options.nugget_min)};
  const std::vector<double> hi = {std::log(options.eta_max), std::log(options.nugget_max)};
  std::vector<double> z = {std::clamp(std::log(eta0), lo[0], hi[0]),
                           std::clamp(std::log(nugget0), lo[1], hi[1])};
  Objective objective;
  objective.distances = &distances;
  objective.x = &x;
  objective.y = &y;
  objective.restricted = options.restricted;
  nlopt::opt opt(nlopt::LN_BOBYQA, 2);
  opt.set_lower_bounds(lo);
  opt.set_upper_bounds(hi);
  opt.set_min_objective(Evaluate, &objective);
  opt.set_xtol_abs(options.tolerance);
  opt.set_maxeval(options.max_evaluations);
  // Steps of a third of the box or less, so the first interpolation points stay inside it.
  opt.set_initial_step({std::min(options.initial_step, (hi[0] - lo[0]) / 3.0),
                        std::min(2.0 * options.initial_step, (hi[1] - lo[1]) / 3.0)});
  double value = HUGE_VAL;
  try {
    opt.optimize(z, value);
  } catch (const std::exception&) {
    // nlopt's roundoff_limited and the like: the best point seen is still the answer.
  }
  if (!std::isfinite(objective.best)) {
    throw std::invalid_argument(
        "estimation: the likelihood could not be evaluated (the correlation matrix is not "
        "positive definite)");
  }
  LikelihoodFit fit;
  ProfiledNeg2LogLikelihood(distances,
                            x,
                            y,
                            std::exp(objective.best_point[0]),
                            std::exp(objective.best_point[1]),
                            options.restricted,
                            &fit);
  fit.evaluations = objective.evaluations;
  const double edge = 10.0 * options.tolerance;
  fit.eta_at_bound =
      objective.best_point[0] <= lo[0] + edge || objective.best_point[0] >= hi[0] - edge;
  fit.nugget_at_bound =
      objective.best_point[1] <= lo[1] + edge || objective.best_point[1] >= hi[1] - edge;
  return fit;
}

}  // namespace ocpb
