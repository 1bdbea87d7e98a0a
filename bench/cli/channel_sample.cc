#include "bench/cli/channel_sample.h"

#include <cmath>
#include <vector>

namespace ocpb {

nlohmann::json ChannelSampleJson(const ChannelQuality& channel, double workspace, double spacing) {
  const int n = static_cast<int>(std::floor(workspace / spacing + 1e-9)) + 1;
  std::vector<double> axis(n);
  for (int i = 0; i < n; ++i) axis[i] = i * spacing;
  nlohmann::json rows = nlohmann::json::array();
  for (int j = 0; j < n; ++j) {
    std::vector<double> row(n);
    for (int i = 0; i < n; ++i) {
      double s = 0.0;
      channel.Evaluate(Eigen::Vector2d(axis[i], axis[j]), &s, nullptr, nullptr);
      row[i] = std::round(1e4 * std::log10(s)) * 1e-4;
    }
    rows.push_back(row);
  }
  return {{"x", axis},
          {"y", axis},
          {"log10_s", rows},
          {"spacing", spacing},
          {"note", "log10 of the channel quality s(q) = E[1/CNR] (W) the problem optimizes over"}};
}

}  // namespace ocpb
