// Kernels of the channel model (problems/channel) on the paper's setting: 50 m x 50 m at 0.1 m
// (250,000 points), 500 samples, seed 1. Accuracy runs report their numbers as counters.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "problems/channel/measurement_sampling.h"
#include "problems/channel/paper_channel.h"

namespace ocpb {
namespace {

// The paper's channel with its predictor and map, built once.
const PaperChannel& Paper() {
  static const PaperChannel c = MakePaperChannel(1, 500);
  return c;
}

// Random points in the workspace, between grid points.
std::vector<Eigen::Vector2d> Points(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.05, 49.95);
  std::vector<Eigen::Vector2d> q(n);
  for (auto& p : q) p = Eigen::Vector2d(u(rng), u(rng));
  return q;
}

void BM_ChannelSimulate(benchmark::State& state) {
  const ChannelSimulator sim{ChannelParameters(), SimulationOptions()};
  std::uint64_t seed = 1;
  for (auto _ : state) benchmark::DoNotOptimize(sim.Simulate(seed++).gain_db.data());
  state.counters["points"] = 250000;
}
BENCHMARK(BM_ChannelSimulate)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

// Including the one-time circulant embedding (eigenvalues by one FFT).
void BM_ChannelSimulateFromScratch(benchmark::State& state) {
  std::uint64_t seed = 1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        SimulateChannel(ChannelParameters(), SimulationOptions(), seed++).gain_db.data());
  }
}
BENCHMARK(BM_ChannelSimulateFromScratch)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

// One estimation from the first m of the 500 samples; args = (method code: 0 binned, 1 ml,
// 2 reml; m). The online loop estimates from 100-400 measurements.
void BM_ChannelEstimate(benchmark::State& state) {
  const PaperChannel& c = Paper();
  EstimationOptions o;
  o.method = EstimationMethodFromCode(static_cast<int>(state.range(0)));
  if (state.range(1) < 500) {  // the online loop's bins (OnlineChannelOptions): 0.2 m bins
    o.bin_width = 1.0;         // have too few pairs with fewer measurements
    o.min_pairs = 20;
  }
  MeasurementSet m = c.measurements;
  m.positions.resize(state.range(1));
  m.values_db.resize(state.range(1));
  EstimationSummary summary;
  for (auto _ : state) {
    benchmark::DoNotOptimize(EstimateChannelParameters(m, c.options.truth, o, &summary).xi);
  }
  state.counters["evaluations"] = summary.likelihood_evaluations;
}
BENCHMARK(BM_ChannelEstimate)
    ->ArgNames({"method", "m"})
    ->ArgsProduct({{0, 1, 2}, {100, 200, 400, 500}})
    ->Unit(benchmark::kMillisecond);

// Mean, variance and s at all 250,000 grid points from 500 samples; arg = threads.
void BM_ChannelPredictGrid(benchmark::State& state) {
  const PaperChannel& c = Paper();
  GridPredictionOptions o;
  o.num_threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    benchmark::DoNotOptimize(PredictOnGrid(*c.predictor, c.truth.grid, o).s.data());
  }
  state.counters["points"] = static_cast<double>(c.truth.grid.num_points());
}
BENCHMARK(BM_ChannelPredictGrid)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

void BM_ChannelBuildMap(benchmark::State& state) {
  const PaperChannel& c = Paper();
  for (auto _ : state) {
    benchmark::DoNotOptimize(ChannelMap::FromPrediction(c.grid, *c.predictor).grid().nx);
  }
}
BENCHMARK(BM_ChannelBuildMap)->Unit(benchmark::kMillisecond);

// One exact s(q) with m = 500; arg = derivative order (0 value, 1 + gradient, 2 + Hessian).
void BM_ChannelExactS(benchmark::State& state) {
  const PaperChannel& c = Paper();
  const std::vector<Eigen::Vector2d> q = Points(1024, 2);
  const int order = static_cast<int>(state.range(0));
  std::size_t k = 0;
  double s;
  Eigen::Vector2d g;
  Eigen::Matrix2d H;
  for (auto _ : state) {
    c.predictor->Evaluate(q[k++ & 1023], &s, order >= 1 ? &g : nullptr, order >= 2 ? &H : nullptr);
    benchmark::DoNotOptimize(s);
  }
}
BENCHMARK(BM_ChannelExactS)->ArgName("order")->DenseRange(0, 2)->Unit(benchmark::kNanosecond);

// One map evaluation; arg = derivative order.
void BM_ChannelMapS(benchmark::State& state) {
  const PaperChannel& c = Paper();
  const std::vector<Eigen::Vector2d> q = Points(1024, 3);
  const int order = static_cast<int>(state.range(0));
  std::size_t k = 0;
  double s;
  Eigen::Vector2d g;
  Eigen::Matrix2d H;
  for (auto _ : state) {
    c.map->Evaluate(q[k++ & 1023], &s, order >= 1 ? &g : nullptr, order >= 2 ? &H : nullptr);
    benchmark::DoNotOptimize(s);
  }
}
BENCHMARK(BM_ChannelMapS)->ArgName("order")->DenseRange(0, 2)->Unit(benchmark::kNanosecond);

// Adding k measurements to a predictor of m: bordered Cholesky update (refactor:0) against
// refactorization (refactor:1). One predictor receives a new batch of k distinct measurements
// each iteration (20 iterations, so m grows by at most 20 k, 2-20%); manual time covers only
// AddMeasurements. Capacity is reserved, as in online use after ReserveCapacity.
void BM_ChannelAddMeasurements(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0)), k = static_cast<int>(state.range(1));
  const auto method = state.range(2) == 0 ? GpChannelPredictor::UpdateMethod::kBorderedCholesky
                                          : GpChannelPredictor::UpdateMethod::kRefactorize;
  const int kIterations = 20;
  const PaperChannel& c = Paper();
  const MeasurementSet all = DrawRandomMeasurements(c.truth, m + kIterations * k, 17);
  MeasurementSet first;
  first.positions.assign(all.positions.begin(), all.positions.begin() + m);
  first.values_db.assign(all.values_db.begin(), all.values_db.begin() + m);
  GpChannelPredictor p(c.estimated, first);
  p.ReserveCapacity(m + kIterations * k);
  int next = m;
  for (auto _ : state) {
    MeasurementSet more;
    more.positions.assign(all.positions.begin() + next, all.positions.begin() + next + k);
    more.values_db.assign(all.values_db.begin() + next, all.values_db.begin() + next + k);
    next += k;
    const auto t0 = std::chrono::steady_clock::now();
    p.AddMeasurements(more, method);
    const auto t1 = std::chrono::steady_clock::now();
    state.SetIterationTime(std::chrono::duration<double>(t1 - t0).count());
    benchmark::DoNotOptimize(p.alpha().data());
  }
}
BENCHMARK(BM_ChannelAddMeasurements)
    ->ArgNames({"m", "k", "refactor"})
    ->ArgsProduct({{100, 200, 500, 1000}, {1, 10}, {0, 1}})
    ->Iterations(20)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

// Accuracy of the grid prediction and of the map against the exact predictor on the paper's
// setting: relative error of s at 20,000 random grid points (grid) and at 20,000 random points
// between grid points (map, both quantities).
void BM_ChannelMapAccuracy(benchmark::State& state) {
  const PaperChannel& c = Paper();
  MapOptions s_options;
  s_options.quantity = MapQuantity::kS;
  const ChannelMap s_map = ChannelMap::FromPrediction(c.grid, *c.predictor, s_options);
  std::vector<double> grid_err, log_err, s_err;
  for (auto _ : state) {
    std::mt19937_64 rng(5);
    const GridSpec& g = c.truth.grid;
    grid_err.clear();
    for (int t = 0; t < 20000; ++t) {
      const int i = static_cast<int>(rng() % g.nx), j = static_cast<int>(rng() % g.ny);
      double s;
      c.predictor->Evaluate(g.Point(i, j), &s, nullptr, nullptr);
      grid_err.push_back(std::abs(c.grid.s(i, j) / s - 1.0));
    }
    log_err.clear();
    s_err.clear();
    for (const Eigen::Vector2d& q : Points(20000, 6)) {
      double s, a, b;
      c.predictor->Evaluate(q, &s, nullptr, nullptr);
      c.map->Evaluate(q, &a, nullptr, nullptr);
      s_map.Evaluate(q, &b, nullptr, nullptr);
      log_err.push_back(std::abs(a / s - 1.0));
      s_err.push_back(std::abs(b / s - 1.0));
    }
  }
  auto quantile = [](std::vector<double> v, double p) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(p * (v.size() - 1))];
  };
  state.counters["grid_rel_max"] = quantile(grid_err, 1.0);
  state.counters["grid_rel_median"] = quantile(grid_err, 0.5);
  state.counters["logs_rel_max"] = quantile(log_err, 1.0);
  state.counters["logs_rel_p99"] = quantile(log_err, 0.99);
  state.counters["logs_rel_median"] = quantile(log_err, 0.5);
  state.counters["s_rel_max"] = quantile(s_err, 1.0);
  state.counters["s_rel_p99"] = quantile(s_err, 0.99);
  state.counters["s_rel_median"] = quantile(s_err, 0.5);
}
BENCHMARK(BM_ChannelMapAccuracy)->Iterations(1)->Unit(benchmark::kSecond);

// Estimator accuracy: mean absolute errors (and their standard errors) over 20 seeds (1..20)
// with 500 samples each on the paper's grid; arg = method code (0 binned, 1 ml, 2 reml). Also
// the mean signed errors of eta and rho and the CPU time of one estimation.
void BM_ChannelEstimatorAccuracy(benchmark::State& state) {
  const ChannelParameters truth;
  const ChannelSimulator sim(truth, SimulationOptions());
  EstimationOptions o;
  o.method = EstimationMethodFromCode(static_cast<int>(state.range(0)));
  const int seeds = 20;
  double mae[5], se[5], bias_eta = 0.0, bias_rho = 0.0, seconds = 0.0;
  for (auto _ : state) {
    std::vector<std::array<double, 5>> err;
    bias_eta = bias_rho = seconds = 0.0;
    for (int s = 1; s <= seeds; ++s) {
      const SimulatedChannel c = sim.Simulate(s);
      const MeasurementSet m = DrawRandomMeasurements(c, 500, s);
      const auto t0 = std::chrono::steady_clock::now();
      const ChannelParameters e = EstimateChannelParameters(m, truth, o);
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      err.push_back({e.k_pl - truth.k_pl,
                     e.n_pl - truth.n_pl,
                     e.xi - truth.xi,
                     e.eta - truth.eta,
                     e.rho - truth.rho});
      bias_eta += (e.eta - truth.eta) / seeds;
      bias_rho += (e.rho - truth.rho) / seeds;
    }
    for (int p = 0; p < 5; ++p) {
      mae[p] = 0.0;
      for (const auto& e : err) mae[p] += std::abs(e[p]) / seeds;
      double var = 0.0;
      for (const auto& e : err) var += std::pow(std::abs(e[p]) - mae[p], 2) / (seeds - 1);
      se[p] = std::sqrt(var / seeds);
    }
  }
  const char* names[5] = {"K_PL", "n_PL", "xi", "eta", "rho"};
  for (int p = 0; p < 5; ++p) {
    state.counters[std::string("mae_") + names[p]] = mae[p];
    state.counters[std::string("se_") + names[p]] = se[p];
  }
  state.counters["bias_eta"] = bias_eta;
  state.counters["bias_rho"] = bias_rho;
  state.counters["ms_per_estimate"] = 1e3 * seconds / seeds;
}
BENCHMARK(BM_ChannelEstimatorAccuracy)
    ->ArgName("method")
    ->DenseRange(0, 2)
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace ocpb
