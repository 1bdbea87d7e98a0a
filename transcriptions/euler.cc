#include "transcriptions/euler.h"

#include "transcriptions/collocation_nlp.h"

namespace ocpb {
namespace {

class EulerNlp final : public CollocationNlp {
 public:
  using CollocationNlp::CollocationNlp;

 protected:
  ControlTrajectory MakeControls(const Mat& values, const TimeGrid& grid) const override {
    return ControlTrajectory::PiecewiseConstant(grid, values);
  }
};

}  // namespace

std::unique_ptr<TranscribedNlp> EulerTranscription::Transcribe(
    const Ocp& ocp, const TranscriptionOptions& options) const {
  ValidateTranscriptionOptions(ocp, options);
  const TimeGrid& grid = options.grid;
  const int N = grid.intervals();
  const bool path = ocp.num_path() > 0;
  CollocationLayout layout;
  layout.nx = ocp.nx();
  layout.nu = ocp.nu();
  for (int k = 0; k < N; ++k) {
    layout.AddState(grid.t(k), k);
    layout.AddControl(grid.t(k));
  }
  layout.AddState(grid.tf(), N);
  for (int k = 0; k < N; ++k) {
    const double h = grid.h(k);
    layout.points.push_back({grid.t(k), k, k, h, h, path});
    layout.defects.push_back({k, {{k, -1.0}, {k + 1, 1.0}}, {{k, h}}});
  }
  if (path) layout.points.push_back({grid.tf(), N, N - 1, 0.0, 0.0, true});
  return std::make_unique<EulerNlp>(ocp, options, std::move(layout), Integrator::kEuler);
}

}  // namespace ocpb
