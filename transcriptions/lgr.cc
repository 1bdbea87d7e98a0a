#include "transcriptions/lgr.h"

#include "transcriptions/collocation_nlp.h"
#include "transcriptions/radau_nodes.h"

namespace ocpb {
namespace {

// Control block k * K + i is U_{k,i}.
class LgrNlp final : public CollocationNlp {
 public:
  LgrNlp(const Ocp& ocp,
         const TranscriptionOptions& options,
         CollocationLayout layout,
         RadauNodes nodes)
      : CollocationNlp(ocp, options, std::move(layout), Integrator::kRk4),
        nodes_(std::move(nodes)) {}

 protected:
  ControlTrajectory MakeControls(const Mat& values, const TimeGrid& grid) const override {
    const TimeGrid g = grid;
    const ControlSet set = ocp().control_set();
    const Vec tau = nodes_.points, bary = nodes_.point_weights;
    const int K = nodes_.K;
    auto fn = [g, values, set, tau, bary, K](double t, ControlTrajectory::Side side, VecRef u) {
      int k = g.Locate(t);
      if (side == ControlTrajectory::Side::kLeft && k > 0 && t <= g.t(k)) --k;
      double s = 2.0 * (t - g.t(k)) / g.h(k) - 1.0;
      s = s < -1.0 ? -1.0 : (s > 1.0 ? 1.0 : s);
      Vec basis(K);
      LagrangeBasis(tau, bary, s, basis);
      u = values.middleCols(k * K, K) * basis;
      set.Project(u);
    };
    return ControlTrajectory::Custom(static_cast<int>(values.rows()),
                                     g,
                                     fn,
                                     "LGR: Lagrange polynomial through the K control values of "
                                     "each interval, projected onto U");
  }

 private:
  RadauNodes nodes_;
};

}  // namespace

std::unique_ptr<TranscribedNlp> LgrTranscription::Transcribe(
    const Ocp& ocp, const TranscriptionOptions& options) const {
  ValidateTranscriptionOptions(ocp, options);
  RadauNodes nodes = ComputeRadauNodes(options.degree);  // validates the degree
  const TimeGrid& grid = options.grid;
  const int N = grid.intervals(), K = nodes.K;
  const bool path = ocp.num_path() > 0;
  CollocationLayout layout;
  layout.nx = ocp.nx();
  layout.nu = ocp.nu();
  for (int k = 0; k < N; ++k) {
    const double h = grid.h(k);
    for (int i = 0; i < K; ++i) {
      const double t = i == 0 ? grid.t(k) : grid.t(k) + 0.5 * h * (nodes.points[i] + 1.0);
      const int j = layout.AddState(t, i == 0 ? k : -1);
      layout.AddControl(t);
      const double w = 0.5 * h * nodes.weights[i];
      layout.points.push_back({t, j, j, w, i == 0 ? w : 0.0, path});
      if (i > 0) {
        layout.states[j].costate_defect = j;  // defect (k, i) has index k * K + i = j
        layout.states[j].costate_scale = -1.0 / nodes.weights[i];
      }
    }
  }
  layout.AddState(grid.tf(), N);
  for (int k = 0; k < N; ++k) {
    for (int i = 0; i < K; ++i) {
      CollocationLayout::Defect d;
      d.interval = k;
      for (int j = 0; j <= K; ++j) d.states.push_back({k * K + j, nodes.differentiation(i, j)});
      d.dynamics.push_back({k * K + i, 0.5 * grid.h(k)});
      layout.defects.push_back(std::move(d));
    }
  }
  return std::make_unique<LgrNlp>(ocp, options, std::move(layout), std::move(nodes));
}

}  // namespace ocpb
