// `ocpbench channel simulate|predict` end to end on a small workspace (12 m x 12 m at 0.25 m:
// 2,304 points): the JSON contract of `predict` (estimated {K_PL, n_PL, xi, eta, rho},
// predict_seconds, points, rmse_db), the files it writes, and bad inputs (exit code 2, one line).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/run_ocpbench.h"

namespace ocpb {
namespace {

using nlohmann::json;
using testing::ProgramRun;
using testing::RunOcpbenchProgram;

std::vector<std::string> ChannelArgs(std::vector<std::string> more = {}) {
  std::vector<std::string> args = {
      "channel", "predict", "--width", "12", "--height", "12", "--resolution", "0.25"};
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// A float32 .npy array written by `channel predict`: its shape and values.
struct Npy {
  std::vector<long> shape;
  std::vector<float> values;
};

Npy ReadNpy(const std::string& path) {
  const std::string bytes = testing::ReadText(path);
  Npy out;
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0) return out;
  const std::size_t header_len =
      static_cast<unsigned char>(bytes[8]) | (static_cast<unsigned char>(bytes[9]) << 8);
  const std::string header = bytes.substr(10, header_len);
  EXPECT_NE(header.find("'descr': '<f4'"), std::string::npos) << header;
  const std::size_t open = header.find("'shape': (");
  std::size_t p = open + 10;
  while (p < header.size() && header[p] != ')') {
    std::size_t used = 0;
    out.shape.push_back(std::stol(header.substr(p), &used));
    p += used;
    while (p < header.size() && (header[p] == ',' || header[p] == ' ')) ++p;
  }
  const std::size_t offset = 10 + header_len;
  out.values.resize((bytes.size() - offset) / sizeof(float));
  std::memcpy(out.values.data(), bytes.data() + offset, out.values.size() * sizeof(float));
  return out;
}

TEST(ChannelCli, PredictJsonContractAndFiles) {
  const std::string dir = testing::FreshDirectory("channel_predict");
  const std::string path = dir + "/report.json";
  const ProgramRun run = RunOcpbenchProgram(
      ChannelArgs({"--samples", "150", "--seed", "3", "--json", path, "--out", dir + "/maps"}));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("channel predict: seed 3, 150 samples, 2304 points"), std::string::npos)
      << run.out;
  const json j = json::parse(testing::ReadText(path));
  // The contract's names and types.
  ASSERT_TRUE(j["estimated"].is_object());
  for (const char* k : {"K_PL", "n_PL", "xi", "eta", "rho"}) {
    ASSERT_TRUE(j["estimated"][k].is_number()) << k;
    EXPECT_TRUE(std::isfinite(j["estimated"][k].get<double>())) << k;
  }
  EXPECT_GT(j["estimated"]["xi"].get<double>(), 0.0);
  EXPECT_GT(j["estimated"]["eta"].get<double>(), 0.0);
  EXPECT_GT(j["estimated"]["rho"].get<double>(), 0.0);
  ASSERT_TRUE(j["predict_seconds"].is_number());
  EXPECT_GE(j["predict_seconds"].get<double>(), 0.0);
  EXPECT_EQ(j["points"], 48 * 48);
  ASSERT_TRUE(j["rmse_db"].is_number());
  EXPECT_EQ(j["seed"], 3);
  EXPECT_EQ(j["samples"], 150);
  // The estimator is recorded (the companion's binned fit by default).
  EXPECT_EQ(j["estimation"]["estimator"], "binned");
  // The same JSON is written next to the maps.
  EXPECT_EQ(json::parse(testing::ReadText(dir + "/maps/predict.json"))["rmse_db"], j["rmse_db"]);

  // rmse_db is the RMSE of the predicted mean against the true channel over the grid: the same
  // number from the two float32 maps (to float32 rounding).
  const Npy truth = ReadNpy(dir + "/maps/true_gain_db.npy");
  const Npy mean = ReadNpy(dir + "/maps/predicted_mean_db.npy");
  ASSERT_EQ(truth.shape, (std::vector<long>{48, 48}));
  ASSERT_EQ(mean.shape, truth.shape);
  ASSERT_EQ(truth.values.size(), 2304u);
  ASSERT_EQ(mean.values.size(), 2304u);
  double sum = 0.0;
  for (std::size_t k = 0; k < truth.values.size(); ++k) {
    sum += std::pow(double(mean.values[k]) - double(truth.values[k]), 2);
  }
  const double rmse = std::sqrt(sum / truth.values.size());
  EXPECT_NEAR(j["rmse_db"].get<double>(), rmse, 1e-4 * rmse);
  // Prediction beats knowing nothing but the mean path loss, and cannot beat the multipath.
  EXPECT_GT(rmse, 0.5);
  EXPECT_LT(rmse, 4.0);
  for (const char* f : {"predicted_variance_db2.npy", "s_map.npy"}) {
    const Npy a = ReadNpy(dir + "/maps/" + f);
    EXPECT_EQ(a.shape, truth.shape) << f;
    EXPECT_TRUE(std::all_of(a.values.begin(), a.values.end(), [](float v) { return v > 0.0f; }))
        << f;
  }

  // Maximum likelihood on the same samples: another estimate, recorded as such; the same grid.
  const std::string ml = dir + "/ml.json";
  const ProgramRun b = RunOcpbenchProgram(ChannelArgs(
      {"--samples", "150", "--seed", "3", "--estimator", "ml", "--no-files", "--json", ml}));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const json jb = json::parse(testing::ReadText(ml));
  EXPECT_EQ(jb["estimation"]["estimator"], "ml");
  EXPECT_GT(jb["estimation"]["likelihood_evaluations"].get<int>(), 5);
  EXPECT_NE(jb["estimated"]["eta"], j["estimated"]["eta"]);
  EXPECT_EQ(jb["points"], j["points"]);
}

TEST(ChannelCli, BadInputsExitTwoWithOneLine) {
  const std::string dir = testing::FreshDirectory("channel_bad");
  const std::string coincident = dir + "/coincident.csv";
  testing::WriteText(coincident, "x_m,y_m,gain_db\n1,1,-70\n2,2,-72\n1,1,-71\n3,4,-75\n");
  const std::string few = dir + "/few.csv";
  testing::WriteText(few, "x_m,y_m,gain_db\n1,1,-70\n2,2,-72\n");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {ChannelArgs({"--samples", "2"}), "--samples must be >= 3"},
      {ChannelArgs({"--samples", "5000"}), "--samples: 5000 measurements need 10000 grid points"},
      // Coincident positions reach the predictor with the true parameters (--oracle) or with
      // maximum likelihood; the binned fit already fails on 4 measurements (too few pairs).
      {ChannelArgs({"--measurements", coincident, "--oracle"}), "coincides with"},
      {ChannelArgs({"--measurements", coincident, "--estimator", "ml"}), "coincides with"},
      {ChannelArgs({"--measurements", coincident}), "distance bins"},
      {ChannelArgs({"--measurements", few}), "at least 3"},
      {ChannelArgs({"--measurements", dir + "/missing.csv"}), "missing.csv"},
      {ChannelArgs({"--estimator", "median"}),
       "unknown estimator 'median' (valid: binned, ml, reml)"},
      {ChannelArgs({"--variance", "approximate"}), "--variance"},
      {ChannelArgs({"--map-quantity", "log"}), "map quantity"},
      {ChannelArgs({"--multipath", "rayleigh"}), "multipath"},
      {ChannelArgs({"--check-points", "-1"}), "--check-points"},
      {ChannelArgs({"--eta", "0"}), "eta"},
      {ChannelArgs({"--samples", "many"}), "--samples"},
      {{"channel", "predict", "--resolution", "0"}, "resolution"},
      {{"channel", "simulate", "--width", "12", "--height", "12", "--rician-k", "0"}, "Rician"},
      {{"channel"}, "A subcommand is required"},
  };
  for (const auto& [args, expected] : cases) {
    const ProgramRun run = RunOcpbenchProgram(args);
    EXPECT_EQ(run.exit_code, 2) << expected << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_EQ(run.err.rfind("ocpbench: error: ", 0), 0u) << run.err;
    EXPECT_NE(run.err.find(expected), std::string::npos) << expected << ": " << run.err;
  }
}

}  // namespace
}  // namespace ocpb
