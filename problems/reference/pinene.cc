#include "problems/reference/pinene.h"

#include <limits>
#include <vector>

namespace ocpb {

EstimationData PineneModel::Data() {
  EstimationData d;
  d.t0 = 0.0;
  d.y0 = Vec::Zero(kStates);
  d.y0[0] = 100.0;
  d.times = {1230.0, 3060.0, 4920.0, 7800.0, 10680.0, 15030.0, 22620.0, 36420.0};
  // COPS 3.0, table of section 5: (y1, ..., y5) at each time above.
  const double z[8][5] = {{88.35, 7.3, 2.3, 0.4, 1.75},
                          {76.4, 15.6, 4.5, 0.7, 2.8},
                          {65.1, 23.1, 5.3, 1.1, 5.8},
                          {50.4, 32.9, 6.0, 1.5, 9.3},
                          {37.5, 42.7, 6.0, 1.9, 12.0},
                          {25.9, 49.1, 5.9, 2.2, 17.0},
                          {14.0, 57.4, 5.1, 2.6, 21.0},
                          {4.5, 63.1, 3.8, 2.9, 25.7}};
  d.observations = Mat(kStates, 8);
  for (int j = 0; j < 8; ++j) {
    for (int s = 0; s < kStates; ++s) d.observations(s, j) = z[j][s];
  }
  d.parameter_lower = Vec::Zero(kParameters);
  d.parameter_upper = Vec::Constant(kParameters, std::numeric_limits<double>::infinity());
  d.parameter_guess = Vec::Constant(kParameters, 1e-5);
  return d;
}

std::unique_ptr<MultiPhaseOcp> MakePinene() {
  return MakeEstimationProblem<PineneModel>("pinene", PineneModel::Data());
}

ProblemInfo PineneProblemInfo() {
  ProblemInfo p;
  p.name = "pinene";
  p.description =
      "COPS isomerization of alpha-pinene: 5 rate constants of a linear network fitted to 8 "
      "observations (least squares; 8 fixed-duration phases)";
  p.make = [](const Parameters&, std::uint64_t) -> std::unique_ptr<Ocp> { return MakePinene(); };
  p.default_intervals = 10;
  p.reference_value = PineneModel::kContinuousOptimum;
  p.reference_source =
      "computed: Ipopt on Hermite-Simpson at N = 20 (Jbar fine) and single shooting with SciPy "
      "DOP853 (rtol 1e-13), agreeing to 1e-8; COPS 3.0's 19.8721 is 0.7 of its last digit below";
  p.additional_references = {
      {PineneModel::kCopsReference,
       "J",
       "continuous",
       0,
       "COPS 3.0 (Dolan, More, Munson, ANL/MCS-TM-273, 2004), problem 5: 19.8721 at nh = 100 with "
       "3-stage Gauss collocation, printed to 6 digits"}};
  p.origin = "COPS 3.0 problem 5 (Box, Hunter, MacGregor, Erjavec 1973)";
  p.hamiltonian_note =
      "not applicable: several phases and no controls (the decisions are the rate constants)";
  p.tags = {"parameter-estimation", "static-parameters", "multi-phase", "mayer"};
  return p;
}

}  // namespace ocpb
