// `ocpbench channel simulate|predict`.
#include "bench/cli/app.h"

#include <sys/resource.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench/cli/case_spec.h"
#include "bench/cli/io.h"
#include "bench/cli/output_place.h"
#include "core/input_file.h"
#include "core/memory_budget.h"
#include "core/timer.h"
#include "problems/channel/channel_memory.h"
#include "problems/channel/measurement_file.h"
#include "problems/channel/measurement_sampling.h"
#include "problems/channel/paper_channel.h"
#include "problems/channel/parameter_estimator.h"

namespace ocpb {
namespace {

// Options shared by both subcommands.
struct CommonArgs {
  std::string seed_text = "1";
  std::uint64_t seed = 1;  ///< seed_text, parsed (ParseSeed) when the command runs
  std::string out = "results/channel";
  std::string json_path;
  double width = 50.0, height = 50.0, resolution = 0.1;
  ChannelParameters truth;
  std::vector<double> base = {5.0, 5.0};
  std::string multipath = "rician";
  double rician_k = 14.56;
  bool no_files = false;
};

struct PredictArgs {
  int samples = 500;
  std::string measurements_csv;
  bool oracle = false;
  std::string estimator = ToString(EstimationOptions().method);
  std::string map_quantity = "log-s";
  std::string variance = "local";
  double radius_eta = 3.5;
  int threads = 0;
  double noise_dbm = -110.0;
  double power_unit_scale = 1e-3;
  int check_points = 0;
};

void AddCommonOptions(CLI::App* cmd, CommonArgs* a) {
  cmd->add_option("--seed",
                  a->seed_text,
                  "realization seed (shadowing, multipath, sample positions; 0 to 2^64 - 1)")
      ->capture_default_str();
  cmd->add_option("--out", a->out, "directory for the maps and the JSON")->capture_default_str();
  cmd->add_option("--json", a->json_path, "also write the JSON report to this file");
  cmd->add_flag("--no-files", a->no_files, "write no maps (only --json, if given)");
  cmd->add_option("--width", a->width, "workspace width, m")->capture_default_str();
  cmd->add_option("--height", a->height, "workspace height, m")->capture_default_str();
  cmd->add_option("--resolution", a->resolution, "grid step, m")->capture_default_str();
  cmd->add_option("--K-PL", a->truth.k_pl, "path-loss gain at 1 m, dB")->capture_default_str();
  cmd->add_option("--n-PL", a->truth.n_pl, "path-loss exponent")->capture_default_str();
  cmd->add_option("--xi", a->truth.xi, "shadowing standard deviation, dB")->capture_default_str();
  cmd->add_option("--eta", a->truth.eta, "shadowing correlation distance, m")
      ->capture_default_str();
  cmd->add_option("--rho", a->truth.rho, "multipath dB standard deviation (lognormal model)")
      ->capture_default_str();
  cmd->add_option("--base", a->base, "base station x y, m")->expected(2)->capture_default_str();
  cmd->add_option("--distance-floor", a->truth.distance_floor, "path-loss distance floor, m")
      ->capture_default_str();
  cmd->add_option("--multipath", a->multipath, "multipath model: rician | lognormal | none")
      ->capture_default_str();
  cmd->add_option("--rician-k", a->rician_k, "Rician K-factor")->capture_default_str();
}

PaperChannelOptions ToOptions(const CommonArgs& a) {
  PaperChannelOptions o;
  o.truth = a.truth;
  o.truth.base_station = Eigen::Vector2d(a.base.at(0), a.base.at(1));
  std::string error;
  if (!o.truth.IsValid(&error)) throw std::invalid_argument(error);
  o.simulation.grid = GridSpec::Workspace(a.width, a.height, a.resolution);
  if (o.simulation.grid.num_points() > 16'000'000) {
    throw std::invalid_argument(
        "workspace: more than 16,000,000 grid points; use a coarser "
        "--resolution");
  }
  const GridSpec& g = o.simulation.grid;
  if (!g.Contains(o.truth.base_station)) {
    throw std::invalid_argument(fmt::format(
        "--base: ({}, {}) lies outside the workspace [{}, {}] x [{}, {}] (--width, --height)",
        o.truth.base_station.x(),
        o.truth.base_station.y(),
        g.x_min,
        g.x_max(),
        g.y_min,
        g.y_max()));
  }
  o.simulation.multipath.model = MultipathModelFromString(a.multipath);
  o.simulation.multipath.rician_k = a.rician_k;
  if (!o.simulation.IsValid(&error)) throw std::invalid_argument(error);
  return o;
}

// A float32 (or float64) little-endian .npy file of shape `shape`, C order.
template <typename T>
std::string Npy(const std::vector<T>& data, const std::vector<long>& shape) {
  static_assert(std::endian::native == std::endian::little, "npy writer assumes little endian");
  std::string dims;
  for (long d : shape) dims += std::to_string(d) + ", ";
  dims.resize(dims.size() - (shape.size() > 1 ? 2 : 1));  // "(500, 500)" but "(7,)"
  std::string header = "{'descr': '<" + std::string(sizeof(T) == 4 ? "f4" : "f8") +
                       "', 'fortran_order': False, 'shape': (" + dims + "), }";
  const std::size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header += '\n';
  std::string out = "\x93NUMPY";
  out += static_cast<char>(1);
  out += static_cast<char>(0);
  const auto len = static_cast<std::uint16_t>(header.size());
  out += static_cast<char>(len & 0xff);
  out += static_cast<char>(len >> 8);
  out += header;
  const std::size_t offset = out.size();
  out.resize(offset + data.size() * sizeof(T));
  std::memcpy(out.data() + offset, data.data(), data.size() * sizeof(T));
  return out;
}

// A grid field (nx x ny, column-major = row-major [j][i]) as float32 of shape (ny, nx).
void WriteField(const std::string& path, const Eigen::MatrixXd& field) {
  std::vector<float> data(static_cast<std::size_t>(field.size()));
  for (Eigen::Index k = 0; k < field.size(); ++k) data[k] = static_cast<float>(field.data()[k]);
  WriteFileAtomically(
      path, Npy(data, {static_cast<long>(field.cols()), static_cast<long>(field.rows())}));
}

nlohmann::json ParametersJson(const ChannelParameters& p) {
  return {{"K_PL", p.k_pl},
          {"n_PL", p.n_pl},
          {"xi", p.xi},
          {"eta", p.eta},
          {"rho", p.rho},
          {"base_station", {p.base_station.x(), p.base_station.y()}},
          {"distance_floor", p.distance_floor}};
}

nlohmann::json CommonJson(const CommonArgs& a,
                          const PaperChannelOptions& o,
                          const SimulatedChannel& c,
                          double simulate_seconds) {
  const GridSpec& g = o.simulation.grid;
  return {{"seed", a.seed},
          {"workspace",
           {{"x_min", g.x_min},
            {"y_min", g.y_min},
            {"width", g.nx * g.resolution},
            {"height", g.ny * g.resolution},
            {"resolution", g.resolution},
            {"nx", g.nx},
            {"ny", g.ny}}},
          {"true", ParametersJson(o.truth)},
          {"multipath",
           {{"model", ToString(o.simulation.multipath.model)},
            {"rician_k", o.simulation.multipath.rician_k}}},
          {"shadowing_clipped_fraction", c.shadowing_clipped_fraction},
          {"simulate_seconds", simulate_seconds},
          {"layout",
           "float32 little-endian .npy of shape (ny, nx); element [j][i] is at (x_min + (i + 0.5) "
           "resolution, y_min + (j + 0.5) resolution); gain in dBm for a 0 dBm transmitter"}};
}

std::string Join(const std::string& dir, const std::string& name) {
  return dir.empty() || dir.back() == '/' ? dir + name : dir + "/" + name;
}

// The output places, checked and claimed before anything is simulated: the --json file, and
// the --out folder with the files written there (unless --no-files).
OutputFolderLock ClaimOutputs(const CommonArgs& a,
                              const std::vector<std::string>& files,
                              const std::string& measurements_csv = "") {
  // No output may be the --measurements file or another output (FilePlan).
  FilePlan plan;
  if (!measurements_csv.empty()) plan.Input(measurements_csv, "--measurements");
  if (!a.no_files) {
    for (const std::string& f : files) plan.Output(Join(a.out, f), "--out");
  }
  if (!a.json_path.empty()) plan.Output(a.json_path, "--json");
  plan.Check();
  if (!a.json_path.empty()) CheckOutputFile(a.json_path, "--json");
  if (a.no_files) return {};
  CheckOutputFolder(a.out, "--out");
  OutputFolderLock lock = OutputFolderLock::Acquire(a.out, "--out", FolderAccess::kExclusive);
  for (const std::string& f : files) CheckOutputFile(Join(a.out, f), "--out");
  return lock;
}

void RunSimulate(const CommonArgs& a) {
  const PaperChannelOptions o = ToOptions(a);
  CheckChannelMemory(0, "--samples", o.simulation.grid.num_points(), "--resolution");
  const OutputFolderLock lock = ClaimOutputs(a, {"true_gain_db.npy", "simulate.json"});
  const Stopwatch watch;
  const SimulatedChannel c = SimulateChannel(o.truth, o.simulation, a.seed);
  const double seconds = watch.wall();
  nlohmann::json j = CommonJson(a, o, c, seconds);
  j["command"] = "channel simulate";
  if (!a.no_files) {
    WriteField(Join(a.out, "true_gain_db.npy"), c.gain_db);
    j["files"] = {{"true_gain_db", "true_gain_db.npy"}};
    WriteFileAtomically(Join(a.out, "simulate.json"), j.dump(1) + "\n");
  }
  if (!a.json_path.empty()) WriteFileAtomically(a.json_path, j.dump(1) + "\n");
  std::cout << fmt::format("channel simulate: seed {}, {} x {} points at {} m in {:.3f} s",
                           a.seed,
                           c.grid.nx,
                           c.grid.ny,
                           c.grid.resolution,
                           seconds)
            << (a.no_files ? "\n" : ", wrote " + Join(a.out, "true_gain_db.npy") + "\n");
}

/// The most grid-prediction threads `--threads` takes.
constexpr int kMaxPredictionThreads = 256;

// kMaxPredictionThreads, or less under a process limit (RLIMIT_NPROC) that would refuse them.
int MostPredictionThreads() {
  struct rlimit limit {};
  if (::getrlimit(RLIMIT_NPROC, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
      limit.rlim_cur < static_cast<rlim_t>(kMaxPredictionThreads)) {
    return std::max(1, static_cast<int>(limit.rlim_cur));
  }
  return kMaxPredictionThreads;
}

// The channel options of `predict`, every value checked.
PaperChannelOptions PredictOptions(const CommonArgs& a, const PredictArgs& p) {
  PaperChannelOptions o = ToOptions(a);
  o.estimate = !p.oracle;
  o.estimation.method = EstimationMethodFromString(p.estimator);
  o.build_map = false;
  o.map.quantity = MapQuantityFromString(p.map_quantity);
  if (p.variance == "local") {
    o.grid_prediction.variance = GridVarianceMethod::kLocal;
  } else if (p.variance == "exact") {
    o.grid_prediction.variance = GridVarianceMethod::kExact;
  } else {
    throw std::invalid_argument("--variance: unknown method '" + p.variance +
                                "' (valid: local, exact)");
  }
  o.grid_prediction.neighborhood_radius_in_eta = p.radius_eta;
  // More threads than a process may start would fail in the middle of the prediction: the
  // count is refused here, before anything is simulated (more threads than cores never speed
  // the prediction up, and its result does not depend on the count).
  const int most = MostPredictionThreads();
  if (p.threads < 0 || p.threads > most) {
    throw std::invalid_argument(
        fmt::format("--threads {}: must be from 0 (all cores) to {} ({})",
                    p.threads,
                    most,
                    most == kMaxPredictionThreads
                        ? "OCPBench's limit: more threads than cores do not speed it up"
                        : "the process limit RLIMIT_NPROC of this user"));
  }
  o.grid_prediction.num_threads = p.threads;
  o.predictor.units.noise_dbm = p.noise_dbm;
  o.predictor.units.power_unit_scale = p.power_unit_scale;
  std::string error;
  if (!o.IsValid(&error)) throw std::invalid_argument(error);
  if (p.check_points < 0) throw std::invalid_argument("--check-points must be >= 0");
  if (p.measurements_csv.empty() && p.samples < 3) {
    throw std::invalid_argument("--samples must be >= 3, got " + std::to_string(p.samples));
  }
  return o;
}

// Simulation, measurements (drawn, or `from_file`), estimation and the exact predictor; then
// the grid prediction and its map.
PaperChannel BuildChannel(std::uint64_t seed,
                          const PaperChannelOptions& o,
                          const PredictArgs& p,
                          MeasurementSet from_file) {
  PaperChannel c;
  if (p.measurements_csv.empty()) {
    c = MakePaperChannel(seed, p.samples, o);
  } else {
    c.seed = seed;
    c.options = o;
    Stopwatch watch;
    c.truth = SimulateChannel(o.truth, o.simulation, seed);
    c.simulate_seconds = watch.wall();
    c.measurements = std::move(from_file);
    const Stopwatch est_watch;
    c.estimated =
        o.estimate ? EstimateChannelParameters(c.measurements, o.truth, o.estimation, &c.estimation)
                   : o.truth;
    c.estimate_seconds = est_watch.wall();
    const Stopwatch factor_watch;
    c.predictor = std::make_shared<GpChannelPredictor>(c.estimated, c.measurements, o.predictor);
    c.factor_seconds = factor_watch.wall();
  }
  c.options.build_map = true;
  c.RefreshMap();
  return c;
}

// What `predict` writes: the estimate, the prediction's timings and ranges, the units.
nlohmann::json PredictJson(const CommonArgs& a,
                           const PredictArgs& p,
                           const PaperChannelOptions& o,
                           const PaperChannel& c) {
  const GridPrediction& g = c.grid;
  nlohmann::json j = CommonJson(a, o, c.truth, c.simulate_seconds);
  j["command"] = "channel predict";
  j["samples"] = c.predictor->num_measurements();
  j["measurements_source"] = p.measurements_csv.empty() ? "random grid points" : p.measurements_csv;
  j["points"] = g.grid.num_points();
  j["estimated"] = {{"K_PL", c.estimated.k_pl},
                    {"n_PL", c.estimated.n_pl},
                    {"xi", c.estimated.xi},
                    {"eta", c.estimated.eta},
                    {"rho", c.estimated.rho}};
  if (o.estimate) {
    j["estimation"] = {{"method", Describe(o.estimation.method)},
                       {"estimator", ToString(o.estimation.method)},
                       {"bins_used", c.estimation.bin_lag.size()},
                       {"residual_variance", c.estimation.residual_variance},
                       {"likelihood_evaluations", c.estimation.likelihood_evaluations},
                       {"neg2_log_likelihood", c.estimation.neg2_log_likelihood},
                       {"xi2_at_bound", c.estimation.xi2_at_bound},
                       {"eta_at_bound", c.estimation.eta_at_bound},
                       {"rho2_floored", c.estimation.rho2_floored},
                       {"bin_width", o.estimation.bin_width},
                       {"min_pairs", o.estimation.min_pairs},
                       {"max_lag", o.estimation.max_lag}};
  } else {
    j["estimation"] = {{"method", "oracle (the true parameters)"}};
  }
  j["predict_seconds"] = g.seconds;
  j["rmse_db"] = c.RmseDb();
  j["estimate_seconds"] = c.estimate_seconds;
  j["factor_seconds"] = c.factor_seconds;
  j["map_seconds"] = c.map_seconds;
  j["grid_method"] = g.method;
  j["map_quantity"] = ToString(o.map.quantity);
  j["provider_map"] = c.map->Describe();
  j["provider_exact"] = c.predictor->Describe();
  j["units"] = {{"noise_dbm", o.predictor.units.noise_dbm},
                {"power_unit_scale", o.predictor.units.power_unit_scale},
                {"s", "E[1/CNR] * power_unit_scale (W per unit (2^R - 1)/K when 1e-3)"}};
  j["s_min"] = g.s.minCoeff();
  j["s_max"] = g.s.maxCoeff();
  j["variance_min"] = g.variance_db2.minCoeff();
  j["variance_max"] = g.variance_db2.maxCoeff();
  return j;
}

// The grid prediction and the map against the exact predictor at `points` random grid points
// and random points between grid points.
nlohmann::json CheckAgainstExact(std::uint64_t seed,
                                 int points,
                                 const PaperChannelOptions& o,
                                 const PaperChannel& c) {
  const GridPrediction& g = c.grid;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> ui(0, g.grid.nx - 1), uj(0, g.grid.ny - 1);
  std::uniform_real_distribution<double> ux(g.grid.Point(0, 0).x(),
                                            g.grid.Point(g.grid.nx - 1, 0).x());
  std::uniform_real_distribution<double> uy(g.grid.Point(0, 0).y(),
                                            g.grid.Point(0, g.grid.ny - 1).y());
  double max_dmean = 0.0, max_dvar = 0.0, max_grid_rel = 0.0;
  std::vector<double> map_rel;
  for (int k = 0; k < points; ++k) {
    const int i = ui(rng), jj = uj(rng);
    PointPrediction pp;
    c.predictor->Predict(g.grid.Point(i, jj), 0, &pp);
    max_dmean = std::max(max_dmean, std::abs(pp.mean_db - g.mean_db(i, jj)));
    max_dvar = std::max(max_dvar, std::abs(pp.variance_db2 - g.variance_db2(i, jj)));
    const double s_exact = ExpectedInverseCnr(pp.mean_db, pp.variance_db2, o.predictor.units);
    max_grid_rel = std::max(max_grid_rel, std::abs(g.s(i, jj) / s_exact - 1.0));
    const Eigen::Vector2d q(ux(rng), uy(rng));
    double se, sm;
    c.predictor->Evaluate(q, &se, nullptr, nullptr);
    c.map->Evaluate(q, &sm, nullptr, nullptr);
    map_rel.push_back(std::abs(sm / se - 1.0));
  }
  std::sort(map_rel.begin(), map_rel.end());
  return {{"points", points},
          {"grid_max_abs_mean_error_db", max_dmean},
          {"grid_max_abs_variance_error_db2", max_dvar},
          {"grid_max_rel_s_error", max_grid_rel},
          {"map_median_rel_s_error", map_rel[map_rel.size() / 2]},
          {"map_p99_rel_s_error", map_rel[map_rel.size() * 99 / 100]},
          {"map_max_rel_s_error", map_rel.back()}};
}

// The maps (.npy), the measurements and predict.json in `dir`; the files' names into `j`.
void WritePredictFiles(const std::string& dir, const PaperChannel& c, nlohmann::json* j) {
  const GridPrediction& g = c.grid;
  WriteField(Join(dir, "true_gain_db.npy"), c.truth.gain_db);
  WriteField(Join(dir, "predicted_mean_db.npy"), g.mean_db);
  WriteField(Join(dir, "predicted_variance_db2.npy"), g.variance_db2);
  WriteField(Join(dir, "s_map.npy"), g.s);
  std::vector<double> m;
  const Eigen::Matrix2Xd& q = c.predictor->positions();
  for (int k = 0; k < c.predictor->num_measurements(); ++k) {
    m.push_back(q(0, k));
    m.push_back(q(1, k));
    m.push_back(c.predictor->values()[k]);
  }
  WriteFileAtomically(Join(dir, "measurements.npy"),
                      Npy(m, {static_cast<long>(c.predictor->num_measurements()), 3L}));
  (*j)["files"] = {{"true_gain_db", "true_gain_db.npy"},
                   {"predicted_mean_db", "predicted_mean_db.npy"},
                   {"predicted_variance_db2", "predicted_variance_db2.npy"},
                   {"s_map", "s_map.npy"},
                   {"measurements", "measurements.npy (float64, m x 3: x, y, gain_db)"}};
  WriteFileAtomically(Join(dir, "predict.json"), j->dump(1) + "\n");
}

void PrintPredictReport(const CommonArgs& a, const PaperChannelOptions& o, const PaperChannel& c) {
  const GridPrediction& g = c.grid;
  std::cout << fmt::format(
      "channel predict: seed {}, {} samples, {} points\n"
      "  estimated K_PL {:.2f} n_PL {:.3f} xi {:.2f} eta {:.2f} rho {:.2f} (true {} {} {} {} {})\n"
      "  predict {:.3f} s ({}), rmse {:.3f} dB, s in [{:.3g}, {:.3g}]\n",
      a.seed,
      c.predictor->num_measurements(),
      g.grid.num_points(),
      c.estimated.k_pl,
      c.estimated.n_pl,
      c.estimated.xi,
      c.estimated.eta,
      c.estimated.rho,
      o.truth.k_pl,
      o.truth.n_pl,
      o.truth.xi,
      o.truth.eta,
      o.truth.rho,
      g.seconds,
      g.method,
      c.RmseDb(),
      g.s.minCoeff(),
      g.s.maxCoeff());
  if (!a.no_files) std::cout << "  wrote " << Join(a.out, "predict.json") << " and maps\n";
}

void RunPredict(const CommonArgs& a, const PredictArgs& p) {
  const PaperChannelOptions o = PredictOptions(a, p);
  // Measurements from a file are read and checked before anything is simulated.
  MeasurementSet from_file;
  const GridSpec& grid = o.simulation.grid;
  if (!p.measurements_csv.empty()) {
    from_file = LoadMeasurementsCsv(p.measurements_csv);
    CheckMeasurementsInside(from_file,
                            Eigen::Vector2d(grid.x_min, grid.y_min),
                            Eigen::Vector2d(grid.x_max(), grid.y_max()),
                            p.measurements_csv);
    CheckChannelMemory(static_cast<double>(from_file.positions.size()),
                       "--measurements " + OneLine(p.measurements_csv),
                       grid.num_points(),
                       "--resolution");
  } else {
    CheckChannelMemory(p.samples, "--samples", grid.num_points(), "--resolution");
    const long eligible = EligibleMeasurementPoints(grid, o.truth);
    if (2L * p.samples > eligible) {
      throw std::invalid_argument(fmt::format(
          "--samples: {} measurements need {} grid points beyond the distance floor of the base "
          "station (twice as many); the grid has {} (--width, --height, --resolution)",
          p.samples,
          2L * p.samples,
          eligible));
    }
  }
  CheckMemoryEstimate(8.0 * p.check_points, "--check-points", "the comparison's points");
  const OutputFolderLock lock = ClaimOutputs(a,
                                             {"true_gain_db.npy",
                                              "predicted_mean_db.npy",
                                              "predicted_variance_db2.npy",
                                              "s_map.npy",
                                              "measurements.npy",
                                              "predict.json"},
                                             p.measurements_csv);
  const PaperChannel c = BuildChannel(a.seed, o, p, std::move(from_file));
  nlohmann::json j = PredictJson(a, p, o, c);
  if (p.check_points > 0) j["check"] = CheckAgainstExact(a.seed, p.check_points, o, c);
  if (!a.no_files) WritePredictFiles(a.out, c, &j);
  if (!a.json_path.empty()) WriteFileAtomically(a.json_path, j.dump(1) + "\n");
  PrintPredictReport(a, o, c);
}

}  // namespace

void AddChannelCommand(CLI::App& app) {
  CLI::App* channel = app.add_subcommand("channel", "Simulate and predict the wireless channel");
  channel->require_subcommand(1);

  auto sim_args = std::make_shared<CommonArgs>();
  CLI::App* simulate = channel->add_subcommand("simulate", "Simulate one channel realization");
  AddCommonOptions(simulate, sim_args.get());
  simulate->callback([sim_args]() {
    sim_args->seed = ParseSeed(sim_args->seed_text, "--seed");
    RunSimulate(*sim_args);
  });

  auto common = std::make_shared<CommonArgs>();
  auto args = std::make_shared<PredictArgs>();
  CLI::App* predict = channel->add_subcommand(
      "predict", "Simulate, sample, estimate and predict the channel on the grid");
  AddCommonOptions(predict, common.get());
  predict->add_option("--samples", args->samples, "measurements at random grid points")
      ->capture_default_str();
  predict->add_option("--measurements",
                      args->measurements_csv,
                      "use measurements from this CSV (x_m,y_m,gain_db) instead of --samples");
  predict->add_flag("--oracle", args->oracle, "predict with the true parameters (no estimation)");
  predict
      ->add_option("--estimator",
                   args->estimator,
                   "parameter estimator: binned (companion) | ml | reml (maximum likelihood)")
      ->capture_default_str();
  predict->add_option("--map-quantity", args->map_quantity, "map interpolates: log-s | s")
      ->capture_default_str();
  predict
      ->add_option("--variance",
                   args->variance,
                   "grid variance: local (neighbourhood of --radius-eta) | exact (slow)")
      ->capture_default_str();
  predict->add_option("--radius-eta", args->radius_eta, "local variance radius in units of eta")
      ->capture_default_str();
  predict->add_option("--threads", args->threads, "grid prediction threads (0: all cores)")
      ->capture_default_str();
  predict->add_option("--noise-dbm", args->noise_dbm, "receiver noise N0, dBm")
      ->capture_default_str();
  predict
      ->add_option(
          "--power-unit-scale", args->power_unit_scale, "s multiplier: 1e-3 gives W, 1 gives mW")
      ->capture_default_str();
  predict
      ->add_option("--check-points",
                   args->check_points,
                   "compare grid and map with the exact predictor at this many random points")
      ->capture_default_str();
  predict->callback([common, args]() {
    common->seed = ParseSeed(common->seed_text, "--seed");
    RunPredict(*common, *args);
  });
}

}  // namespace ocpb
