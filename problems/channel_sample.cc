#include "problems/channel_sample.h"

#include <cmath>
#include <vector>

#include "problems/comm_path2d.h"

namespace ocpb {

FieldSample SampleChannel(const ChannelQuality& channel, double workspace, double spacing) {
  // At most kMaxFieldSamplePoints nodes: a coarser spacing for a workspace beyond 500 spacings.
  const double per_side = std::sqrt(kMaxFieldSamplePoints) - 1.0;
  if (workspace / spacing > per_side) spacing = workspace / per_side;
  const int n = static_cast<int>(std::floor(workspace / spacing + 1e-9)) + 1;
  FieldSample f;
  f.quantity = "log10_s";
  f.note = "log10 of the channel quality s(q) = E[1/CNR] (W) the problem optimizes over";
  f.spacing = spacing;
  f.x.resize(n);
  for (int i = 0; i < n; ++i) f.x[i] = i * spacing;
  f.y = f.x;
  f.values.resize(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      double s = 0.0;
      channel.Evaluate(Eigen::Vector2d(f.x[i], f.y[j]), &s, nullptr, nullptr);
      f.values(j, i) = std::round(1e4 * std::log10(s)) * 1e-4;
    }
  }
  return f;
}

std::optional<FieldSample> SampleCommPath2dChannel(const Ocp& ocp) {
  const auto* comm = dynamic_cast<const CommPath2d*>(&ocp);
  if (comm == nullptr) return std::nullopt;
  return SampleChannel(comm->channel(), comm->options().workspace);
}

}  // namespace ocpb
