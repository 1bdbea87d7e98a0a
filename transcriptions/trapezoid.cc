#include "transcriptions/trapezoid.h"

#include "transcriptions/collocation_nlp.h"

namespace ocpb {
namespace {

class TrapezoidNlp final : public CollocationNlp {
 public:
  using CollocationNlp::CollocationNlp;

 protected:
  std::optional<CollocationInterpolant> mesh_interpolant() const override {
    return CollocationInterpolant::kTrapezoid;
  }
  ControlTrajectory MakeControls(const Mat& values, const TimeGrid& grid) const override {
    return ControlTrajectory::PiecewiseLinear(grid, values);
  }
};

}  // namespace

std::unique_ptr<TranscribedNlp> TrapezoidTranscription::Transcribe(
    const Ocp& ocp, const TranscriptionOptions& options) const {
  ValidateTranscriptionOptions(ocp, options);
  const TimeGrid& grid = options.grid;
  const int N = grid.intervals();
  const bool path = ocp.num_path() > 0;
  CollocationLayout layout;
  layout.nx = ocp.nx();
  layout.nu = ocp.nu();
  for (int k = 0; k <= N; ++k) {
    layout.AddState(grid.t(k), k);
    layout.AddControl(grid.t(k));
    const double left = k > 0 ? 0.5 * grid.h(k - 1) : 0.0;
    const double right = k < N ? 0.5 * grid.h(k) : 0.0;
    layout.points.push_back({grid.t(k), k, k, left + right, right, path});
  }
  for (int k = 0; k < N; ++k) {
    const double h = grid.h(k);
    layout.defects.push_back({k, {{k, -1.0}, {k + 1, 1.0}}, {{k, 0.5 * h}, {k + 1, 0.5 * h}}});
  }
  return std::make_unique<TrapezoidNlp>(ocp, options, std::move(layout), Integrator::kRk4);
}

}  // namespace ocpb
