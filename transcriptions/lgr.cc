#include "transcriptions/lgr.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "transcriptions/collocation_nlp.h"
#include "transcriptions/lgr_mesh_error.h"
#include "transcriptions/radau_nodes.h"

namespace ocpb {
namespace {

// The LGR data of every interval: its degree, its nodes, and the index of its first state and
// control block (interval k's point i is block first[k] + i; x(tf) is the last state block).
struct LgrIntervals {
  std::vector<int> degrees;
  std::vector<int> first;
  std::vector<RadauNodes> nodes;  // one per interval (copies of the cache's, small)
};

// Interval k's controls are blocks first[k] .. first[k] + K_k - 1, its states the same blocks
// and first[k] + K_k (the next interval's first point, or x(tf)).
class LgrNlp final : public CollocationNlp {
 public:
  LgrNlp(const Ocp& ocp,
         const TranscriptionOptions& options,
         CollocationLayout layout,
         std::shared_ptr<const LgrIntervals> intervals)
      : CollocationNlp(ocp, options, std::move(layout), Integrator::kRk4),
        intervals_(std::move(intervals)) {}

  std::vector<int> IntervalDegrees() const override { return intervals_->degrees; }
  /// At a fixed degree K the estimate decreases as h^(K+1): the smallest degree's exponent.
  int IntervalErrorOrder() const override {
    return *std::min_element(intervals_->degrees.begin(), intervals_->degrees.end()) + 1;
  }

  /// The state polynomial of each interval (LgrStateAt) on the solution's horizon, the left
  /// limit at a mesh node from the interval before it (the same value: x(t_k+1) is interval k's
  /// last support point).
  ControlTrajectory StateTrajectory(ConstVecRef zhat) const override {
    const TimeGrid g = SolutionMesh(zhat);
    const Mat X = States(zhat);
    const std::shared_ptr<const LgrIntervals> iv = intervals_;
    auto fn = [g, X, iv](double t, ControlTrajectory::Side side, VecRef x) {
      int k = g.Locate(t);
      if (side == ControlTrajectory::Side::kLeft && k > 0 && t <= g.t(k)) --k;
      const double s = std::clamp(2.0 * (t - g.t(k)) / g.h(k) - 1.0, -1.0, 1.0);
      LgrStateAt(iv->nodes[k], X.middleCols(iv->first[k], iv->degrees[k] + 1), s, x);
    };
    return ControlTrajectory::Custom(
        static_cast<int>(X.rows()), g, fn, "LGR state polynomial of each interval");
  }

 protected:
  Vec SchemeIntervalErrors(ConstVecRef zhat) const override {
    return LgrIntervalErrors(
        ocp(), SolutionMesh(zhat), intervals_->degrees, States(zhat), Controls(zhat));
  }

  ControlTrajectory MakeControls(const Mat& values, const TimeGrid& grid) const override {
    const TimeGrid g = grid;
    const ControlSet set = ocp().control_set();
    const std::shared_ptr<const LgrIntervals> iv = intervals_;
    auto fn = [g, values, set, iv](double t, ControlTrajectory::Side side, VecRef u) {
      int k = g.Locate(t);
      if (side == ControlTrajectory::Side::kLeft && k > 0 && t <= g.t(k)) --k;
      const double s = std::clamp(2.0 * (t - g.t(k)) / g.h(k) - 1.0, -1.0, 1.0);
      const RadauNodes& nodes = iv->nodes[k];
      Vec basis(nodes.K);
      LagrangeBasis(nodes.points, nodes.point_weights, s, basis);
      u = values.middleCols(iv->first[k], nodes.K) * basis;
      set.Project(u);
    };
    return ControlTrajectory::Custom(static_cast<int>(values.rows()),
                                     g,
                                     fn,
                                     "LGR: Lagrange polynomial through the K control values of "
                                     "each interval, projected onto U");
  }

 private:
  std::shared_ptr<const LgrIntervals> intervals_;
};

}  // namespace

std::unique_ptr<TranscribedNlp> LgrTranscription::Transcribe(
    const Ocp& ocp, const TranscriptionOptions& options) const {
  ValidateTranscriptionOptions(ocp, options);
  const TimeGrid& grid = options.grid;
  const int N = grid.intervals();
  if (!options.degrees.empty() && static_cast<int>(options.degrees.size()) != N) {
    throw std::invalid_argument("lgr: degrees must have one entry per grid interval (" +
                                std::to_string(N) + "), got " +
                                std::to_string(options.degrees.size()));
  }
  LgrIntervals iv;
  iv.degrees = options.degrees.empty() ? std::vector<int>(N, options.degree) : options.degrees;
  if (options.mesh.enabled()) {
    // The estimate uses K + 1 points.
    for (int K : iv.degrees) {
      if (K + 1 > kMaxRadauPoints) {
        throw std::invalid_argument("lgr: with mesh_tolerance > 0 every degree must be <= " +
                                    std::to_string(kMaxRadauPoints - 1) + ", got " +
                                    std::to_string(K));
      }
    }
  }
  RadauNodeCache cache;
  const bool path = ocp.num_path() > 0;
  CollocationLayout layout;
  layout.nx = ocp.nx();
  layout.nu = ocp.nu();
  for (int k = 0; k < N; ++k) {
    const RadauNodes& nodes = cache.Get(iv.degrees[k]);  // validates the degree
    iv.nodes.push_back(nodes);
    iv.first.push_back(static_cast<int>(layout.states.size()));
    const double h = grid.h(k);
    for (int i = 0; i < nodes.K; ++i) {
      const double t = i == 0 ? grid.t(k) : grid.t(k) + 0.5 * h * (nodes.points[i] + 1.0);
      const int j = layout.AddState(t, i == 0 ? k : -1);
      layout.AddControl(t);
      const double w = 0.5 * h * nodes.weights[i];
      layout.points.push_back({t, j, j, w, i == 0 ? w : 0.0, path});
      if (i > 0) {
        layout.states[j].costate_defect = j;  // defect (k, i) is added as the j-th below
        layout.states[j].costate_scale = -1.0 / nodes.weights[i];
      }
    }
  }
  layout.AddState(grid.tf(), N);
  for (int k = 0; k < N; ++k) {
    const RadauNodes& nodes = iv.nodes[k];
    const int first = iv.first[k];
    for (int i = 0; i < nodes.K; ++i) {
      CollocationLayout::Defect d;
      d.interval = k;
      for (int j = 0; j <= nodes.K; ++j) {
        d.states.push_back({first + j, nodes.differentiation(i, j)});
      }
      d.dynamics.push_back({first + i, 0.5 * grid.h(k)});
      layout.defects.push_back(std::move(d));
    }
  }
  return std::make_unique<LgrNlp>(
      ocp, options, std::move(layout), std::make_shared<const LgrIntervals>(std::move(iv)));
}

}  // namespace ocpb
