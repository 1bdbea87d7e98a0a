#include "problems/channel/grid_predictor.h"

#include <fftw3.h>
#include <Eigen/Cholesky>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <vector>

#include "core/invalid.h"
#include "core/timer.h"
#include "problems/channel/fftw_planner.h"
#include "problems/channel/shadowing_simulator.h"

namespace ocpb {

const char* ToString(GridVarianceMethod method) {
  return method == GridVarianceMethod::kLocal ? "local" : "exact";
}

bool GridPredictionOptions::IsValid(std::string* error) const {
  if (!(neighborhood_radius_in_eta > 0.0) || !std::isfinite(neighborhood_radius_in_eta)) {
    return Invalid(error, "neighborhood_radius_in_eta must be finite and > 0");
  }
  if (tile_points < 2) return Invalid(error, "tile_points must be >= 2");
  if (far_field_order < 4) return Invalid(error, "far_field_order must be >= 4");
  if (num_threads < 0) return Invalid(error, "num_threads must be >= 0");
  if (min_fft_nx < 0 || min_fft_ny < 0) {
    return Invalid(error, "min_fft_nx and min_fft_ny must be >= 0");
  }
  return true;
}

namespace {

// Barycentric Lagrange basis of the p Chebyshev points of the first kind on [a, b], evaluated
// at x_0..x_{n-1}: an n x p matrix.
Eigen::MatrixXd ChebyshevBasis(const Eigen::VectorXd& nodes_t,
                               double a,
                               double b,
                               const Eigen::VectorXd& x) {
  const int p = static_cast<int>(nodes_t.size());
  Eigen::VectorXd w(p);
  for (int c = 0; c < p; ++c) {
    w[c] = ((c % 2 == 0) ? 1.0 : -1.0) * std::sin((2 * c + 1) * std::numbers::pi / (2.0 * p));
  }
  Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(x.size(), p);
  for (Eigen::Index r = 0; r < x.size(); ++r) {
    const double t = (2.0 * x[r] - a - b) / (b - a);
    int exact = -1;
    double sum = 0.0;
    for (int c = 0; c < p; ++c) {
      const double diff = t - nodes_t[c];
      if (diff == 0.0) {
        exact = c;
        break;
      }
      basis(r, c) = w[c] / diff;
      sum += basis(r, c);
    }
    if (exact >= 0) {
      basis.row(r).setZero();
      basis(r, exact) = 1.0;
    } else {
      basis.row(r) /= sum;
    }
  }
  return basis;
}

// sum_k w_k table(|i - i_k|, |j - j_k|) at every grid point (i, j): the linear convolution of
// the weight image with the kernel table, by real FFTs of size >= (2 nx - 1) x (2 ny - 1)
// (no wrap-around in the part kept; larger when min_nx, min_ny ask for it).
Eigen::MatrixXd LatticeConvolution(const Eigen::MatrixXd& table,
                                   const std::vector<int>& lattice,
                                   const Eigen::VectorXd& weights,
                                   int min_nx,
                                   int min_ny) {
  const int nx = static_cast<int>(table.rows()), ny = static_cast<int>(table.cols());
  const int mx = NextFftSize(2 * std::max(nx, min_nx) - 1);
  const int my = NextFftSize(2 * std::max(ny, min_ny) - 1);
  const int cx = mx / 2 + 1;
  const std::size_t real_n = static_cast<std::size_t>(mx) * my;
  const std::size_t complex_n = static_cast<std::size_t>(cx) * my;
  auto real_alloc = [](std::size_t n) {
    double* p = fftw_alloc_real(n);
    if (p == nullptr) throw std::runtime_error("grid prediction: out of memory (FFT)");
    return std::unique_ptr<double, void (*)(void*)>(p, fftw_free);
  };
  auto complex_alloc = [](std::size_t n) {
    fftw_complex* p = fftw_alloc_complex(n);
    if (p == nullptr) throw std::runtime_error("grid prediction: out of memory (FFT)");
    return std::unique_ptr<fftw_complex, void (*)(void*)>(p, fftw_free);
  };
  auto image = real_alloc(real_n);
  auto kernel = real_alloc(real_n);
  auto image_hat = complex_alloc(complex_n);
  auto kernel_hat = complex_alloc(complex_n);
  const std::shared_ptr<const RealFft2dPlans> plans = CachedRealFft2dPlans(my, mx);
  std::fill(image.get(), image.get() + real_n, 0.0);
  std::fill(kernel.get(), kernel.get() + real_n, 0.0);
  for (std::size_t k = 0; k < static_cast<std::size_t>(weights.size()); ++k) {
    if (lattice[2 * k] < 0) continue;
    image.get()[static_cast<std::size_t>(lattice[2 * k + 1]) * mx + lattice[2 * k]] += weights[k];
  }
  for (int dj = -(ny - 1); dj <= ny - 1; ++dj) {
    const std::size_t row = static_cast<std::size_t>((dj + my) % my) * mx;
    for (int di = -(nx - 1); di <= nx - 1; ++di) {
      kernel.get()[row + (di + mx) % mx] = table(std::abs(di), std::abs(dj));
    }
  }
  fftw_execute_dft_r2c(plans->forward, image.get(), image_hat.get());
  fftw_execute_dft_r2c(plans->forward, kernel.get(), kernel_hat.get());
  const double scale = 1.0 / static_cast<double>(real_n);
  for (std::size_t k = 0; k < complex_n; ++k) {
    const double ar = image_hat.get()[k][0], ai = image_hat.get()[k][1];
    const double br = kernel_hat.get()[k][0], bi = kernel_hat.get()[k][1];
    image_hat.get()[k][0] = scale * (ar * br - ai * bi);
    image_hat.get()[k][1] = scale * (ar * bi + ai * br);
  }
  fftw_execute_dft_c2r(plans->backward, image_hat.get(), image.get());
  Eigen::MatrixXd out(nx, ny);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) out(i, j) = image.get()[static_cast<std::size_t>(j) * mx + i];
  }
  return out;
}

class GridWorker {
 public:
  GridWorker(const GpChannelPredictor& predictor,
             const GridSpec& grid,
             const GridPredictionOptions& options,
             GridPrediction* out)
      : pred_(predictor), grid_(grid), options_(options), out_(out) {
    const ChannelParameters& par = predictor.parameters();
    xi2_ = par.xi * par.xi;
    rho2_ = par.rho * par.rho;
    inv_eta_ = 1.0 / par.eta;
    radius_ = options.neighborhood_radius_in_eta * par.eta;
    tiles_x_ = (grid.nx + options.tile_points - 1) / options.tile_points;
    tiles_y_ = (grid.ny + options.tile_points - 1) / options.tile_points;
    const int p = options.far_field_order;
    cheb_t_.resize(p);
    for (int c = 0; c < p; ++c) cheb_t_[c] = std::cos((2 * c + 1) * std::numbers::pi / (2.0 * p));

    // Measurements at grid points use a table of kernel values by lattice offset.
    const Eigen::Matrix2Xd& Q = pred_.positions();
    const int m = static_cast<int>(Q.cols());
    lattice_.assign(2 * m, -1);
    bool any_lattice = false;
    for (int k = 0; k < m; ++k) {
      const double fi = (Q(0, k) - grid.x_min) / grid.resolution - 0.5;
      const double fj = (Q(1, k) - grid.y_min) / grid.resolution - 0.5;
      const double ri = std::round(fi), rj = std::round(fj);
      if (std::abs(fi - ri) < 1e-6 && std::abs(fj - rj) < 1e-6 && ri >= 0 && ri < grid.nx &&
          rj >= 0 && rj < grid.ny) {
        lattice_[2 * k] = static_cast<int>(ri);
        lattice_[2 * k + 1] = static_cast<int>(rj);
        any_lattice = true;
      }
    }
    // The kernel table and Omega are filled by SetupJob, the mean's lattice part by Convolve.
    if (any_lattice) table_.resize(grid.nx, grid.ny);
    if (options.variance == GridVarianceMethod::kLocal) omega_.resize(m, m);
  }

  // The jobs below are kept out of line so that a profile (results/plotting/callgrind_counts.py)
  // attributes instructions to each round. Setup jobs, each independent of the others: the kernel
  // table's columns dj (when some measurements lie on the lattice), then the columns c of Omega
  // (local variance).
  int num_setup_jobs() const {
    return static_cast<int>(table_.cols()) + static_cast<int>(omega_.cols());
  }
  [[gnu::noinline]] void SetupJob(int job) {
    if (job < table_.cols()) {
      const int dj = job;
      const double h = grid_.resolution;
      for (int di = 0; di < grid_.nx; ++di) {
        table_(di, dj) =
            xi2_ * std::exp(-inv_eta_ * h * std::sqrt(double(di) * di + double(dj) * dj));
      }
      return;
    }
    // Entry (r, c) and (c, r) of Omega belong to the job of column min(r, c).
    const int c = job - static_cast<int>(table_.cols());
    const Eigen::Matrix2Xd& Q = pred_.positions();
    for (int r = c; r < omega_.rows(); ++r) {
      omega_(r, c) = omega_(c, r) = xi2_ * std::exp(-inv_eta_ * (Q.col(r) - Q.col(c)).norm());
    }
  }
  bool has_lattice() const { return table_.size() > 0; }
  // The mean's part from the measurements on the lattice, by FFT (after the setup jobs).
  [[gnu::noinline]] void Convolve() {
    lattice_mean_ = LatticeConvolution(
        table_, lattice_, pred_.alpha(), options_.min_fft_nx, options_.min_fft_ny);
  }

  int num_tiles() const { return tiles_x_ * tiles_y_; }

  [[gnu::noinline]] void Tile(int tile) const {
    const int T = options_.tile_points;
    const int i0 = (tile % tiles_x_) * T, j0 = (tile / tiles_x_) * T;
    const int tx = std::min(T, grid_.nx - i0), ty = std::min(T, grid_.ny - j0);
    const int P = tx * ty;
    const double h = grid_.resolution;
    const Eigen::Vector2d p0 = grid_.Point(i0, j0);
    const double xa = p0.x(), xb = p0.x() + (tx - 1) * h;
    const double ya = p0.y(), yb = p0.y() + (ty - 1) * h;
    Eigen::ArrayXd X(P), Y(P);
    for (int j = 0; j < ty; ++j) {
      for (int i = 0; i < tx; ++i) {
        X[i + tx * j] = xa + i * h;
        Y[i + tx * j] = ya + j * h;
      }
    }
    const Eigen::Matrix2Xd& Q = pred_.positions();
    const Eigen::VectorXd& alpha = pred_.alpha();
    const int m = static_cast<int>(Q.cols());
    const bool exact = options_.variance == GridVarianceMethod::kExact;

    std::vector<int> near, far_other;
    near.reserve(m);
    for (int k = 0; k < m; ++k) {
      const double dx = std::max({xa - Q(0, k), 0.0, Q(0, k) - xb});
      const double dy = std::max({ya - Q(1, k), 0.0, Q(1, k) - yb});
      if (exact || dx * dx + dy * dy < radius_ * radius_) {
        near.push_back(k);
      } else if (lattice_[2 * k] < 0) {
        far_other.push_back(k);
      }
    }
    const int n = static_cast<int>(near.size());

    // Near kernel columns (P x n) and the near part of the mean.
    Eigen::MatrixXd KT(P, n);
    for (int c = 0; c < n; ++c) {
      const int k = near[c];
      if (lattice_[2 * k] >= 0) {
        Eigen::ArrayXd col(P);
        for (int j = 0; j < ty; ++j) {
          Eigen::Map<Eigen::ArrayXd> row(col.data() + tx * j, tx);
          row.setZero();
          AddLatticeRow(k, i0, j0 + j, tx, 1.0, &row);
        }
        KT.col(c) = col.matrix();
      } else {
        KT.col(c) =
            xi2_ * (-inv_eta_ * ((X - Q(0, k)).square() + (Y - Q(1, k)).square()).sqrt()).exp();
      }
    }
    // Mean: the measurements off the lattice near ... (Finish adds the lattice part, which
    // Convolve computes meanwhile on another thread)
    Eigen::ArrayXd mean = Eigen::ArrayXd::Zero(P);
    for (int c = 0; c < n; ++c) {
      if (lattice_[2 * near[c]] < 0) mean += alpha[near[c]] * KT.col(c).array();
    }
    // ... and far by Chebyshev interpolation of the smooth far field, or directly.
    if (!far_other.empty()) {
      const int p = options_.far_field_order;
      const bool cheb = tx > p && ty > p && radius_ >= 2.0 * std::max(xb - xa, yb - ya);
      if (cheb) {
        Eigen::ArrayXd NX(p * p), NY(p * p);
        for (int b = 0; b < p; ++b) {
          for (int a = 0; a < p; ++a) {
            NX[a + p * b] = 0.5 * (xa + xb) + 0.5 * (xb - xa) * cheb_t_[a];
            NY[a + p * b] = 0.5 * (ya + yb) + 0.5 * (yb - ya) * cheb_t_[b];
          }
        }
        Eigen::ArrayXd G = Eigen::ArrayXd::Zero(p * p);
        for (int k : far_other) {
          G += alpha[k] *
               (-inv_eta_ * ((NX - Q(0, k)).square() + (NY - Q(1, k)).square()).sqrt()).exp();
        }
        G *= xi2_;
        Eigen::VectorXd xs(tx), ys(ty);
        for (int i = 0; i < tx; ++i) xs[i] = xa + i * h;
        for (int j = 0; j < ty; ++j) ys[j] = ya + j * h;
        const Eigen::MatrixXd bx = ChebyshevBasis(cheb_t_, xa, xb, xs);
        const Eigen::MatrixXd by = ChebyshevBasis(cheb_t_, ya, yb, ys);
        const Eigen::Map<const Eigen::MatrixXd> gm(G.data(), p, p);
        const Eigen::MatrixXd f = bx * gm * by.transpose();  // tx x ty
        mean += Eigen::Map<const Eigen::ArrayXd>(f.data(), P);
      } else {
        for (int k : far_other) {
          mean += (alpha[k] * xi2_) *
                  (-inv_eta_ * ((X - Q(0, k)).square() + (Y - Q(1, k)).square()).sqrt()).exp();
        }
      }
    }

    // Variance.
    Eigen::ArrayXd variance = Eigen::ArrayXd::Constant(P, xi2_ + rho2_);
    if (n > 0) {
      if (exact) {
        pred_.cholesky_factor()
            .transpose()
            .triangularView<Eigen::Upper>()
            .solveInPlace<Eigen::OnTheRight>(KT);
      } else {
        Eigen::MatrixXd phi(n, n);
        for (int c = 0; c < n; ++c) {
          for (int r = c; r < n; ++r) phi(r, c) = omega_(near[r], near[c]);
          phi(c, c) += rho2_;
        }
        Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt(phi);
        if (llt.info() != Eigen::Success) {
          throw std::runtime_error("grid prediction: local Phi is not positive definite");
        }
        llt.matrixU().solveInPlace<Eigen::OnTheRight>(KT);  // KT U^{-1} = (L^{-1} KT^T)^T
      }
      variance -= KT.rowwise().squaredNorm().array();
    }

    for (int j = 0; j < ty; ++j) {
      for (int i = 0; i < tx; ++i) {
        out_->mean_db(i0 + i, j0 + j) = mean[i + tx * j];  // Finish completes it
        out_->variance_db2(i0 + i, j0 + j) = variance[i + tx * j];
      }
    }
  }

  // The tile's mean (+ lattice part + path loss) and s, after Tile and Convolve.
  [[gnu::noinline]] void Finish(int tile) const {
    const int T = options_.tile_points;
    const int i0 = (tile % tiles_x_) * T, j0 = (tile / tiles_x_) * T;
    const int tx = std::min(T, grid_.nx - i0), ty = std::min(T, grid_.ny - j0);
    const QualityUnits& units = pred_.options().units;
    for (int j = j0; j < j0 + ty; ++j) {
      for (int i = i0; i < i0 + tx; ++i) {
        double mean = out_->mean_db(i, j);
        if (lattice_mean_.size() > 0) mean = lattice_mean_(i, j) + mean;
        const double mu = pred_.PathLossMean(grid_.Point(i, j), nullptr, nullptr) + mean;
        out_->mean_db(i, j) = mu;
        out_->s(i, j) = ExpectedInverseCnr(mu, out_->variance_db2(i, j), units);
      }
    }
  }

 private:
  // row[i] += weight * kernel(point(i_start + i, j) - q_k) for i < count, q_k on the lattice.
  void AddLatticeRow(
      int k, int i_start, int j, int count, double weight, Eigen::Map<Eigen::ArrayXd>* row) const {
    const int ik = lattice_[2 * k], jk = lattice_[2 * k + 1];
    const double* t = &table_(0, std::abs(j - jk));
    // Points left of ik: offsets ik - i (decreasing); right: i - ik (increasing).
    const int split = std::clamp(ik - i_start, 0, count);  // points with i < ik
    for (int i = 0; i < split; ++i) (*row)[i] += weight * t[ik - i_start - i];
    const int first = i_start + split - ik;  // offset of point `split`
    for (int i = split; i < count; ++i) (*row)[i] += weight * t[first + (i - split)];
  }

  const GpChannelPredictor& pred_;
  const GridSpec& grid_;
  const GridPredictionOptions& options_;
  GridPrediction* out_;
  double xi2_, rho2_, inv_eta_, radius_;
  int tiles_x_, tiles_y_;
  Eigen::VectorXd cheb_t_;
  std::vector<int> lattice_;      // (i, j) of each measurement on the grid lattice, or -1
  Eigen::MatrixXd table_;         // kernel by lattice offset (di, dj)
  Eigen::MatrixXd omega_;         // Omega of all measurements (local variance)
  Eigen::MatrixXd lattice_mean_;  // Psi^T alpha over the lattice measurements, nx x ny
};

// Runs job(0), ..., job(count - 1) on up to `threads` threads (this one included), each job
// once, in increasing order of start; rethrows the first exception after all threads stopped.
// When the system refuses a thread (a process or memory limit), the jobs run on the threads
// already started (every job does the same arithmetic on any thread, so the result is the
// same). Returns the number of threads the jobs ran on.
int RunJobs(int count, int threads, const std::function<void(int)>& job) {
  std::atomic<int> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto run = [&]() {
    try {
      for (int j = next++; j < count; j = next++) job(j);
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      next = count;
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::min(threads, count); ++t) {
    try {
      pool.emplace_back(run);
    } catch (const std::system_error&) {
      break;  // never std::terminate: go on with the threads there are
    }
  }
  run();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return static_cast<int>(pool.size()) + 1;
}

}  // namespace

GridPrediction PredictOnGrid(const GpChannelPredictor& predictor,
                             const GridSpec& grid,
                             const GridPredictionOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("grid prediction options: " + error);
  if (!grid.IsValid(&error)) throw std::invalid_argument("grid prediction: " + error);
  const Stopwatch watch;
  GridPrediction out;
  out.grid = grid;
  out.mean_db.resize(grid.nx, grid.ny);
  out.variance_db2.resize(grid.nx, grid.ny);
  out.s.resize(grid.nx, grid.ny);
  GridWorker worker(predictor, grid, options, &out);
  int threads = options.num_threads > 0 ? options.num_threads
                                        : static_cast<int>(std::thread::hardware_concurrency());
  threads = std::clamp(threads, 1, std::max(1, worker.num_tiles()));
  // Three rounds of independent jobs on `threads` threads; every job does the same arithmetic
  // whichever thread runs it, so the result does not depend on the thread count. Round 2 runs
  // the FFT convolution (job 0) next to the tiles, which do not need it.
  const int tiles = worker.num_tiles();
  // The fewest threads any round ran on (the system may refuse some: see RunJobs).
  int ran = threads;
  auto round = [&](int count, const std::function<void(int)>& job) {
    const int used = RunJobs(count, threads, job);
    if (used < std::min(threads, count)) ran = std::min(ran, used);
  };
  round(worker.num_setup_jobs(), [&](int job) { worker.SetupJob(job); });
  const int convolve = worker.has_lattice() ? 1 : 0;
  round(convolve + tiles, [&](int job) {
    if (job < convolve) {
      worker.Convolve();
    } else {
      worker.Tile(job - convolve);
    }
  });
  round(tiles, [&](int job) { worker.Finish(job); });
  out.seconds = watch.wall();
  std::ostringstream os;
  os << ToString(options.variance);
  if (options.variance == GridVarianceMethod::kLocal) {
    os << " R=" << options.neighborhood_radius_in_eta << "eta";
  }
  os << " tile=" << options.tile_points << " cheb=" << options.far_field_order
     << " threads=" << threads;
  if (ran < threads) os << " (the system started only " << ran << ")";
  out.method = os.str();
  return out;
}

}  // namespace ocpb
