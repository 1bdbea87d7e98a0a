#include "problems/reference/methanol.h"

#include <limits>
#include <vector>

namespace ocpb {

EstimationData MethanolModel::Data() {
  EstimationData d;
  d.t0 = 0.0;
  d.y0 = Eigen::Vector3d(1.0, 0.0, 0.0);
  d.times = {0.0,
             0.050,
             0.065,
             0.080,
             0.123,
             0.233,
             0.273,
             0.354,
             0.397,
             0.418,
             0.502,
             0.553,
             0.681,
             0.750,
             0.916,
             0.937,
             1.122};
  // COPS 3.0, table of section 13: (y1, y2, y3) at each time above.
  const double z[17][3] = {{1.0000, 0.0000, 0.0000},
                           {0.7085, 0.1621, 0.0811},
                           {0.5971, 0.1855, 0.0965},
                           {0.5537, 0.1989, 0.1198},
                           {0.3684, 0.2845, 0.1535},
                           {0.1712, 0.3491, 0.2097},
                           {0.1198, 0.3098, 0.2628},
                           {0.0747, 0.3576, 0.2467},
                           {0.0529, 0.3347, 0.2884},
                           {0.0415, 0.3388, 0.2757},
                           {0.0261, 0.3557, 0.3167},
                           {0.0208, 0.3483, 0.2954},
                           {0.0085, 0.3836, 0.2950},
                           {0.0053, 0.3611, 0.2937},
                           {0.0019, 0.3609, 0.2831},
                           {0.0018, 0.3485, 0.2846},
                           {0.0006, 0.3698, 0.2899}};
  d.observations = Mat(kStates, 17);
  for (int j = 0; j < 17; ++j) {
    for (int s = 0; s < kStates; ++s) d.observations(s, j) = z[j][s];
  }
  d.parameter_lower = Vec::Zero(kParameters);
  d.parameter_upper = Vec::Constant(kParameters, std::numeric_limits<double>::infinity());
  d.parameter_guess = Vec::Ones(kParameters);
  return d;
}

std::unique_ptr<MultiPhaseOcp> MakeMethanol() {
  return MakeEstimationProblem<MethanolModel>("methanol", MethanolModel::Data());
}

ProblemInfo MethanolProblemInfo() {
  ProblemInfo p;
  p.name = "methanol";
  p.description =
      "COPS methanol to hydrocarbons: 5 rate constants fitted to 17 observations (least "
      "squares; 16 fixed-duration phases)";
  p.make = [](const Parameters&, std::uint64_t) -> std::unique_ptr<Ocp> { return MakeMethanol(); };
  p.default_intervals = 10;
  p.reference_value = MethanolModel::kContinuousOptimum;
  p.reference_source =
      "computed: single shooting with SciPy DOP853 (rtol 1e-13); Ipopt on Hermite-Simpson at N = "
      "20 is 2e-8 above it (Jbar fine); COPS 3.0's 9.02229e-3 agrees to its 6 digits";
  p.additional_references = {
      {MethanolModel::kCopsReference,
       "J",
       "continuous",
       0,
       "COPS 3.0 (Dolan, More, Munson, ANL/MCS-TM-273, 2004), problem 13: 9.02229e-3 at nh = 100 "
       "with 3-stage Gauss collocation, printed to 6 digits"}};
  p.origin = "COPS 3.0 problem 13";
  p.hamiltonian_note =
      "not applicable: several phases and no controls (the decisions are the rate constants)";
  p.tags = {"parameter-estimation", "static-parameters", "multi-phase", "mayer"};
  return p;
}

}  // namespace ocpb
