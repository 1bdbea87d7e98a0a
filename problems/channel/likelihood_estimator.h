// Maximum-likelihood estimation of the channel parameters (an alternative to the companion's
// binned least squares; see parameter_estimator.h for the entry point and the choice).
#pragma once

#include <Eigen/Core>

namespace ocpb {

/// The Gaussian model of m measurements y = H beta + e, H = [1, -10 log10 d_i],
/// beta = (K_PL, n_PL), e ~ N(0, sigma^2 R(eta, f)) with the correlation matrix
///   R_ij = (1 - f) exp(-|q_i - q_j| / eta) + f [i == j],
/// i.e. xi^2 = (1 - f) sigma^2 (shadowing) and rho^2 = f sigma^2 (multipath, the nugget).
/// beta and sigma^2 have closed forms for given (eta, f) (generalized least squares), so the
/// likelihood is maximized over two parameters only: (log eta, log f) in a box, by NLopt's
/// BOBYQA (derivative-free, bounded), from a given start.
///
/// Each evaluation costs one Cholesky factorization of R (m^3 / 3 flops: about 5 ms at m = 500,
/// 0.3 ms at m = 200 on this machine) and m^2 / 2 exponentials.
struct LikelihoodFitOptions {
  bool restricted = false;               ///< true: REML (the likelihood of residual contrasts)
  double eta_min = 0.05, eta_max = 5.0;  ///< bounds on eta, m
  double nugget_min = 1e-4;              ///< bounds on f = rho^2 / (xi^2 + rho^2)
  double nugget_max = 0.99;
  double tolerance = 1e-2;  ///< absolute tolerance on log eta and log f (1%: far below the
                            ///< statistical error)
  int max_evaluations = 300;
  /// BOBYQA's first step in log eta and log f (capped at a third of the box); smaller when the
  /// start is already close (a previous estimate with a few more measurements).
  double initial_step = 0.5;
};

struct LikelihoodFit {
  double k_pl = 0.0, n_pl = 0.0;     ///< beta, the GLS estimate at the optimum
  double sigma2 = 0.0;               ///< total variance xi^2 + rho^2, dB^2
  double eta = 0.0;                  ///< m
  double nugget = 0.0;               ///< f
  double neg2_log_likelihood = 0.0;  ///< -2 log L (profiled; the full constant included)
  int evaluations = 0;
  bool eta_at_bound = false, nugget_at_bound = false;
};

/// -2 log of the profiled (restricted) likelihood at (eta, f), +inf if R is not positive
/// definite. `distances` is the m x m matrix |q_i - q_j| (only the lower triangle is read), `x`
/// the regressor -10 log10 d_i, `y` the values. On return (if not null) `fit` holds beta,
/// sigma^2, eta and f.
double ProfiledNeg2LogLikelihood(const Eigen::MatrixXd& distances,
                                 const Eigen::VectorXd& x,
                                 const Eigen::VectorXd& y,
                                 double eta,
                                 double nugget,
                                 bool restricted,
                                 LikelihoodFit* fit = nullptr);

/// Maximizes the likelihood from (eta0, nugget0) (clamped into the box). Throws
/// std::invalid_argument if no evaluation is finite.
LikelihoodFit FitLikelihood(const Eigen::MatrixXd& distances,
                            const Eigen::VectorXd& x,
                            const Eigen::VectorXd& y,
                            double eta0,
                            double nugget0,
                            const LikelihoodFitOptions& options);

}  // namespace ocpb
