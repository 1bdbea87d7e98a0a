#include "problems/channel/parameter_estimator.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/invalid.h"
#include "problems/channel/likelihood_estimator.h"

namespace ocpb {

bool EstimationOptions::IsValid(std::string* error) const {
  if (!(bin_width > 0.0) || !std::isfinite(bin_width)) {
    return Invalid(error, "bin_width must be > 0");
  }
  if (min_pairs < 1) return Invalid(error, "min_pairs must be >= 1");
  if (!(max_lag > bin_width) || !std::isfinite(max_lag)) {
    return Invalid(error, "max_lag must be > bin_width");
  }
  if (!(xi2_max > 0.0) || !std::isfinite(xi2_max)) return Invalid(error, "xi2_max must be > 0");
  if (!(eta_min > 0.0) || !(eta_max > eta_min) || !std::isfinite(eta_max)) {
    return Invalid(error, "need 0 < eta_min < eta_max");
  }
  if (!(rho2_floor > 0.0) || !std::isfinite(rho2_floor)) {
    return Invalid(error, "rho2_floor must be > 0");
  }
  return true;
}

void ValidateMeasurements(const MeasurementSet& measurements, const ChannelParameters& known) {
  const std::size_t m = measurements.positions.size();
  if (measurements.values_db.size() != m) {
    throw std::invalid_argument("measurements: " + std::to_string(m) + " positions but " +
                                std::to_string(measurements.values_db.size()) + " values");
  }
  if (m < 3) {
    throw std::invalid_argument("need at least 3 measurements, got " + std::to_string(m));
  }
  for (std::size_t i = 0; i < m; ++i) {
    const Eigen::Vector2d& q = measurements.positions[i];
    if (!q.allFinite() || !std::isfinite(measurements.values_db[i])) {
      throw std::invalid_argument("measurement " + std::to_string(i) +
                                  " has a non-finite position or value");
    }
    const double d = (q - known.base_station).norm();
    if (d < known.distance_floor) {
      std::ostringstream os;
      os << "measurement " << i << " at (" << q.x() << ", " << q.y() << ") lies within the "
         << "distance floor " << known.distance_floor << " m of the base station ("
         << known.base_station.x() << ", " << known.base_station.y() << ")";
      throw std::invalid_argument(os.str());
    }
  }
}

namespace {

struct Bin {
  double sum_rr = 0.0, sum_d = 0.0;
  long n = 0;
};

// Best clamped xi^2 and the cost for a given eta.
double FitCost(const std::vector<double>& d,
               const std::vector<double>& c,
               const std::vector<double>& w,
               double eta,
               double xi2_max,
               double* xi2) {
  double num = 0.0, den = 0.0;
  for (std::size_t b = 0; b < d.size(); ++b) {
    const double e = std::exp(-d[b] / eta);
    num += w[b] * c[b] * e;
    den += w[b] * e * e;
  }
  *xi2 = den > 0.0 ? std::clamp(num / den, 0.0, xi2_max) : 0.0;
  double cost = 0.0;
  for (std::size_t b = 0; b < d.size(); ++b) {
    const double r = c[b] - *xi2 * std::exp(-d[b] / eta);
    cost += w[b] * r * r;
  }
  return cost;
}

// Step 1: the regressor, the values and the ordinary least-squares path loss.
struct PathLossFit {
  Eigen::VectorXd x, y, r;  // -10 log10 d, values, residuals y - H theta
  double k_pl = 0.0, n_pl = 0.0;
};

PathLossFit OrdinaryLeastSquares(const MeasurementSet& measurements,
                                 const ChannelParameters& known) {
  const int m = static_cast<int>(measurements.positions.size());
  PathLossFit f;
  f.x.resize(m);
  f.y.resize(m);
  for (int i = 0; i < m; ++i) {
    f.x[i] = -10.0 * std::log10(known.FlooredDistance(measurements.positions[i]));
    f.y[i] = measurements.values_db[i];
  }
  // Centred normal equations: well conditioned.
  const double xm = f.x.mean(), ym = f.y.mean();
  const double sxx = (f.x.array() - xm).square().sum();
  if (!(sxx > 1e-12 * m)) {
    throw std::invalid_argument(
        "estimation: all measurements are at the same distance from the base station, which "
        "does not determine n_PL");
  }
  f.n_pl = ((f.x.array() - xm) * (f.y.array() - ym)).sum() / sxx;
  f.k_pl = ym - f.n_pl * xm;
  f.r = f.y - (f.k_pl + f.n_pl * f.x.array()).matrix();
  return f;
}

// Steps 2-4 of the binned procedure.
ChannelParameters Binned(const MeasurementSet& measurements,
                         const ChannelParameters& known,
                         const EstimationOptions& options,
                         const PathLossFit& ols,
                         EstimationSummary* summary) {
  const int m = static_cast<int>(measurements.positions.size());
  const Eigen::VectorXd& r = ols.r;

  // 2. Binned residual covariance.
  const int num_bins = static_cast<int>(std::ceil(options.max_lag / options.bin_width));
  std::vector<Bin> bins(num_bins);
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector2d& qi = measurements.positions[i];
    for (int j = i + 1; j < m; ++j) {
      const double d = (qi - measurements.positions[j]).norm();
      if (!(d > 0.0) || d >= options.max_lag) continue;
      const int b = std::min(static_cast<int>(d / options.bin_width), num_bins - 1);
      bins[b].sum_rr += r[i] * r[j];
      bins[b].sum_d += d;
      ++bins[b].n;
    }
  }
  std::vector<double> lag, cov, weight;
  std::vector<long> pairs;
  for (const Bin& b : bins) {
    if (b.n < options.min_pairs) continue;
    lag.push_back(b.sum_d / b.n);
    cov.push_back(b.sum_rr / b.n);
    pairs.push_back(b.n);
    weight.push_back(static_cast<double>(b.n) / lag.back());
  }
  if (lag.size() < 2) {
    throw std::invalid_argument("estimation: fewer than 2 distance bins have " +
                                std::to_string(options.min_pairs) +
                                " measurement pairs; use more measurements");
  }

  // 3. Weighted fit: log-spaced scan of eta, then golden section around the best.
  const int kScan = 200;
  const double log_lo = std::log(options.eta_min), log_hi = std::log(options.eta_max);
  auto eta_at = [&](int k) { return std::exp(log_lo + (log_hi - log_lo) * k / (kScan - 1)); };
  int best = 0;
  double best_cost = INFINITY, xi2 = 0.0;
  for (int k = 0; k < kScan; ++k) {
    const double cost = FitCost(lag, cov, weight, eta_at(k), options.xi2_max, &xi2);
    if (cost < best_cost) {
      best_cost = cost;
      best = k;
    }
  }
  double a = std::log(eta_at(std::max(best - 1, 0)));
  double b = std::log(eta_at(std::min(best + 1, kScan - 1)));
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c1 = b - g * (b - a), c2 = a + g * (b - a);
  double f1 = FitCost(lag, cov, weight, std::exp(c1), options.xi2_max, &xi2);
  double f2 = FitCost(lag, cov, weight, std::exp(c2), options.xi2_max, &xi2);
  for (int it = 0; it < 60 && b - a > 1e-10; ++it) {
    if (f1 < f2) {
      b = c2;
      c2 = c1;
      f2 = f1;
      c1 = b - g * (b - a);
      f1 = FitCost(lag, cov, weight, std::exp(c1), options.xi2_max, &xi2);
    } else {
      a = c1;
      c1 = c2;
      f1 = f2;
      c2 = a + g * (b - a);
      f2 = FitCost(lag, cov, weight, std::exp(c2), options.xi2_max, &xi2);
    }
  }
  double eta = std::exp(0.5 * (a + b));
  double cost = FitCost(lag, cov, weight, eta, options.xi2_max, &xi2);
  if (best_cost < cost) {  // the scan point itself was better (flat or boundary optimum)
    eta = eta_at(best);
    cost = FitCost(lag, cov, weight, eta, options.xi2_max, &xi2);
  }

  // 4. Multipath power.
  const double residual_variance = r.squaredNorm() / m;
  const double rho2 = std::max(residual_variance - xi2, options.rho2_floor);

  ChannelParameters est = known;
  est.k_pl = ols.k_pl;
  est.n_pl = ols.n_pl;
  est.xi = std::sqrt(xi2);
  est.eta = eta;
  est.rho = std::sqrt(rho2);
  if (summary != nullptr) {
    summary->bin_lag = lag;
    summary->bin_covariance = cov;
    summary->bin_pairs = pairs;
    summary->residual_variance = residual_variance;
    summary->fit_cost = cost;
    summary->xi2_at_bound = xi2 <= 0.0 || xi2 >= options.xi2_max;
    summary->eta_at_bound =
        eta <= options.eta_min * (1.0 + 1e-9) || eta >= options.eta_max * (1.0 - 1e-9);
    summary->rho2_floored = residual_variance - xi2 < options.rho2_floor;
  }
  if (!(est.xi > 0.0)) {
    throw std::invalid_argument(
        "estimation: the residuals show no spatial correlation (xi = 0); the Gaussian-process "
        "predictor needs xi > 0");
  }
  return est;
}

// Maximum likelihood (ML or REML), started from the binned estimate when it exists.
ChannelParameters Likelihood(const MeasurementSet& measurements,
                             const ChannelParameters& known,
                             const EstimationOptions& options,
                             const PathLossFit& ols,
                             EstimationSummary* summary) {
  double eta0 = 1.0, nugget0 = 0.2;
  if (options.likelihood_start.has_value()) {
    const ChannelParameters& p = *options.likelihood_start;
    eta0 = p.eta;
    nugget0 = p.rho * p.rho / (p.xi * p.xi + p.rho * p.rho);
  } else {
    try {
      const ChannelParameters start = Binned(measurements, known, options, ols, summary);
      const double xi2 = start.xi * start.xi, rho2 = start.rho * start.rho;
      eta0 = start.eta;
      nugget0 = rho2 / (xi2 + rho2);
      summary->started_from_binned = true;
    } catch (const std::invalid_argument&) {
      // Too few pairs per bin or no correlation in the binned residuals: the default start.
    }
  }
  if (!(eta0 > 0.0) || !std::isfinite(eta0)) eta0 = 1.0;
  if (!(nugget0 > 0.0 && nugget0 < 1.0)) nugget0 = 0.2;  // also NaN from xi = rho = 0
  const int m = static_cast<int>(measurements.positions.size());
  Eigen::MatrixXd distances(m, m);
  for (int j = 0; j < m; ++j) {
    for (int i = j; i < m; ++i) {
      distances(i, j) = (measurements.positions[i] - measurements.positions[j]).norm();
    }
  }
  LikelihoodFitOptions lo;
  lo.restricted = options.method == EstimationMethod::kRestrictedMaximumLikelihood;
  lo.eta_min = options.eta_min;
  lo.eta_max = options.eta_max;
  if (options.likelihood_start.has_value()) lo.initial_step = 0.15;
  const LikelihoodFit fit = FitLikelihood(distances, ols.x, ols.y, eta0, nugget0, lo);
  const double xi2 = (1.0 - fit.nugget) * fit.sigma2;
  const double rho2 = std::max(fit.nugget * fit.sigma2, options.rho2_floor);
  ChannelParameters est = known;
  est.k_pl = fit.k_pl;
  est.n_pl = fit.n_pl;
  est.xi = std::sqrt(xi2);
  est.eta = fit.eta;
  est.rho = std::sqrt(rho2);
  summary->residual_variance = ols.r.squaredNorm() / m;
  summary->fit_cost = NAN;
  summary->xi2_at_bound = false;
  summary->eta_at_bound = fit.eta_at_bound;
  summary->rho2_floored = fit.nugget * fit.sigma2 < options.rho2_floor;
  summary->neg2_log_likelihood = fit.neg2_log_likelihood;
  summary->likelihood_evaluations = fit.evaluations;
  return est;
}

}  // namespace

const char* ToString(EstimationMethod method) {
  switch (method) {
    case EstimationMethod::kBinnedLeastSquares:
      return "binned";
    case EstimationMethod::kMaximumLikelihood:
      return "ml";
    case EstimationMethod::kRestrictedMaximumLikelihood:
      return "reml";
  }
  return "?";
}

const char* Describe(EstimationMethod method) {
  switch (method) {
    case EstimationMethod::kBinnedLeastSquares:
      return "companion two-stage least squares (OLS path loss; weighted fit of the binned "
             "residual covariance; rho^2 = mean r^2 - xi^2)";
    case EstimationMethod::kMaximumLikelihood:
      return "maximum likelihood (GLS path loss and variance profiled out; BOBYQA over log eta "
             "and log nugget fraction, started from the binned estimate)";
    case EstimationMethod::kRestrictedMaximumLikelihood:
      return "restricted maximum likelihood (REML; GLS path loss and variance profiled out; "
             "BOBYQA over log eta and log nugget fraction, started from the binned estimate)";
  }
  return "?";
}

EstimationMethod EstimationMethodFromString(const std::string& name) {
  for (EstimationMethod m : {EstimationMethod::kBinnedLeastSquares,
                             EstimationMethod::kMaximumLikelihood,
                             EstimationMethod::kRestrictedMaximumLikelihood}) {
    if (name == ToString(m)) return m;
  }
  throw std::invalid_argument("unknown estimator '" + name + "' (valid: binned, ml, reml)");
}

EstimationMethod EstimationMethodFromCode(int code) {
  if (code < 0 || code > 2) {
    throw std::invalid_argument("estimator code must be 0 (binned), 1 (ml) or 2 (reml), got " +
                                std::to_string(code));
  }
  return static_cast<EstimationMethod>(code);
}

ChannelParameters EstimateChannelParameters(const MeasurementSet& measurements,
                                            const ChannelParameters& known,
                                            const EstimationOptions& options,
                                            EstimationSummary* summary) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("estimation options: " + error);
  if (!known.base_station.allFinite() || !(known.distance_floor > 0.0)) {
    throw std::invalid_argument("estimation: base station must be finite and distance floor > 0");
  }
  ValidateMeasurements(measurements, known);
  EstimationSummary local;
  EstimationSummary* s = summary != nullptr ? summary : &local;
  *s = EstimationSummary();
  s->method = options.method;
  const PathLossFit ols = OrdinaryLeastSquares(measurements, known);
  if (options.method == EstimationMethod::kBinnedLeastSquares) {
    return Binned(measurements, known, options, ols, s);
  }
  return Likelihood(measurements, known, options, ols, s);
}

}  // namespace ocpb
