#include "problems/reference/free_time_brachistochrone.h"

#include <cmath>
#include <memory>

#include "problems/reference/free_time_parameters.h"

namespace ocpb {

std::vector<ParameterSpec> FreeTimeBrachistochrone::ParameterSpecs() {
  return FreeFinalTimeParameterSpecs(10.0);
}

FreeTimeBrachistochrone::FreeTimeBrachistochrone(const Parameters& params) {
  SetDimensions(3, 2, 2, 0);
  SetHorizon(0.0, params.Scalar("tf"));
  CheckFreeFinalTimeParameters(params);
  SetFreeFinalTime(params.Scalar("tf_min"), params.Scalar("tf_max"));
  SetInitialState(Vec::Zero(3));
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
  ControlSet disc;
  disc.AddBall(2, 1.0);
  SetControlSet(disc);
}

void FreeTimeBrachistochrone::MinimizeHamiltonian(double,
                                                  ConstVecRef x,
                                                  ConstVecRef p,
                                                  VecRef u) const {
  // H = 1 + s^T w with s = (p_x v, p_y v + p_v g): minimized over the disc at w = -s / |s|.
  const double s1 = p[0] * x[2], s2 = p[1] * x[2] + p[2] * kGravity;
  const double norm = std::hypot(s1, s2);
  if (norm > 0.0) {
    u[0] = -s1 / norm;
    u[1] = -s2 / norm;
  } else {
    u.setZero();
  }
}

Vec FreeTimeBrachistochrone::NominalControl() const { return Vec::Constant(2, std::sqrt(0.5)); }

ProblemInfo FreeTimeBrachistochroneProblemInfo() {
  ProblemInfo p;
  p.name = "brachistochrone-free-time";
  p.description =
      "brachistochrone to (2, 2) with the final time free (no time scaling), min T, |w| <= 1";
  p.parameters = FreeTimeBrachistochrone::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<FreeTimeBrachistochrone>(params);
  };
  p.default_intervals = 100;
  p.reference_value = FreeTimeBrachistochrone::kReferenceTime;
  p.reference_source =
      "the cycloid through (2, 2), re-derived (project notes 2.10; PSOPT brac1: 0.8247591)";
  p.hamiltonian_note =
      "free final time: the descent keeps tf fixed (not applicable); indirect-newton and the NLP "
      "solvers on a collocation transcription take it; the time-scaled 'brachistochrone' poses it "
      "for every method";
  p.tags = {"smooth", "free-time", "control-constrained"};
  return p;
}

}  // namespace ocpb
