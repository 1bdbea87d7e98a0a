#include "transcriptions/hermite_simpson.h"

#include <algorithm>

#include "transcriptions/collocation_nlp.h"

namespace ocpb {
namespace {

// Control blocks are numbered 2k (node k) and 2k + 1 (midpoint of interval k).
class HermiteSimpsonNlp final : public CollocationNlp {
 public:
  using CollocationNlp::CollocationNlp;

 protected:
  std::optional<CollocationInterpolant> mesh_interpolant() const override {
    return CollocationInterpolant::kHermiteSimpson;
  }
  ControlTrajectory MakeControls(const Mat& values, const TimeGrid& grid) const override {
    const TimeGrid g = grid;
    const ControlSet set = ocp().control_set();
    auto fn = [g, values, set](double t, ControlTrajectory::Side side, VecRef u) {
      int k = g.Locate(t);
      if (side == ControlTrajectory::Side::kLeft && k > 0 && t <= g.t(k)) --k;
      const double s = std::clamp((t - g.t(k)) / g.h(k), 0.0, 1.0);
      const double l0 = 2.0 * (s - 0.5) * (s - 1.0);
      const double lm = -4.0 * s * (s - 1.0);
      const double l1 = 2.0 * s * (s - 0.5);
      u = l0 * values.col(2 * k) + lm * values.col(2 * k + 1) + l1 * values.col(2 * k + 2);
      set.Project(u);
    };
    return ControlTrajectory::Custom(
        static_cast<int>(values.rows()),
        g,
        fn,
        "Hermite-Simpson: quadratic through u_k, u_k+1/2, u_k+1 per interval, projected onto U");
  }
};

}  // namespace

std::unique_ptr<TranscribedNlp> HermiteSimpsonTranscription::Transcribe(
    const Ocp& ocp, const TranscriptionOptions& options) const {
  ValidateTranscriptionOptions(ocp, options);
  const TimeGrid& grid = options.grid;
  const int N = grid.intervals();
  const bool path = ocp.num_path() > 0;
  CollocationLayout layout;
  layout.nx = ocp.nx();
  layout.nu = ocp.nu();
  // State, control and point index 2k is node k, 2k + 1 the midpoint of interval k.
  for (int k = 0; k <= N; ++k) {
    const double left = k > 0 ? grid.h(k - 1) / 6.0 : 0.0;
    const double right = k < N ? grid.h(k) / 6.0 : 0.0;
    layout.AddState(grid.t(k), k);
    layout.AddControl(grid.t(k));
    layout.points.push_back({grid.t(k), 2 * k, 2 * k, left + right, right, path});
    if (k == N) break;
    const double h = grid.h(k), tm = grid.t(k) + 0.5 * h;
    const int m = layout.AddState(tm, -1);
    layout.AddControl(tm);
    layout.points.push_back({tm, m, m, 4.0 * h / 6.0, 0.0, path});
    // -lambda_Simpson is Simpson's mean (p_k + 4 p_m + p_k+1)/6 of the costate over the interval.
    layout.states[m].costate_defect = 2 * k;
    layout.states[m].costate_scale = -1.5;
    layout.states[m].costate_blocks = {{2 * k, -0.25}, {2 * k + 2, -0.25}};
  }
  for (int k = 0; k < N; ++k) {
    const double h = grid.h(k);
    const int a = 2 * k, m = 2 * k + 1, b = 2 * k + 2;
    layout.defects.push_back(
        {k, {{a, -1.0}, {b, 1.0}}, {{a, h / 6.0}, {m, 4.0 * h / 6.0}, {b, h / 6.0}}});
    layout.defects.push_back({k, {{m, 1.0}, {a, -0.5}, {b, -0.5}}, {{a, h / 8.0}, {b, -h / 8.0}}});
  }
  return std::make_unique<HermiteSimpsonNlp>(ocp, options, std::move(layout), Integrator::kRk4);
}

}  // namespace ocpb
