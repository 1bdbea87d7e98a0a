#include "problems/library/classic/tumor_antiangiogenesis.h"

#include <algorithm>
#include <memory>

#include "problems/reference/free_time_parameters.h"

namespace ocpb {

std::vector<ParameterSpec> TumorAntiangiogenesis::ParameterSpecs() {
  return {
      {"tf",
       {1.0},
       "nominal final time: where methods start (within [tf_min, tf_max])",
       0.0,
       1e6,
       true},
      {"tf_min", {0.01}, "lower bound of the free final time", 0.0, 1e6, true},
      {"tf_max", {5.0}, "upper bound of the free final time", 0.0, 1e6, true},
  };
}

TumorAntiangiogenesis::TumorAntiangiogenesis(const Parameters& params) {
  const double tf = params.Scalar("tf");
  SetHorizon(0.0, tf);
  CheckFreeFinalTimeParameters(params);
  SetFreeFinalTime(params.Scalar("tf_min"), params.Scalar("tf_max"));
  const double cap = Capacity();
  SetInitialState(Eigen::Vector3d(cap / 2.0, cap / 4.0, 0.0));
  ControlSet set;
  set.AddBox(Vec::Constant(1, 0.0), Vec::Constant(1, kMaxDose));
  SetControlSet(set);
  SetStateBounds(Eigen::Vector3d(0.01, 0.01, 0.0), Eigen::Vector3d(cap, cap, kTotalDose));
  nominal_dose_ = std::min(kMaxDose, kTotalDose / tf);
}

ProblemInfo TumorAntiangiogenesisProblemInfo() {
  ProblemInfo p;
  p.name = "tumor-antiangiogenesis";
  p.description =
      "tumour anti-angiogenesis (Ledzewicz-Schaettler, Betts 10.141): min tumour volume p(T), "
      "dose 0 <= u <= 75, total dose <= 15, T free";
  p.parameters = TumorAntiangiogenesis::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<TumorAntiangiogenesis>(params);
  };
  p.default_intervals = 200;
  p.reference_value = TumorAntiangiogenesis::kReferenceCost;
  p.reference_source =
      "Betts 2010 (Practical Methods for Optimal Control and Estimation Using Nonlinear "
      "Programming, 2nd ed.), example 10.141 (section 8.17): p(T*) = 7571.6712, T* = 1.1961336";
  p.additional_references = {
      {TumorAntiangiogenesis::kReferenceTime,
       "tf",
       "continuous",
       0,
       "Betts 2010, example 10.141: T* = 1.1961336"},
      {7571.67158,
       "J",
       "continuous",
       0,
       "Patterson & Rao, GPOPS-II (ACM TOMS 41(1), 2014), tumor anti-angiogenesis example: "
       "p(T) = 7571.67158"}};
  p.origin = "Ledzewicz & Schaettler; Betts 2010 example 10.141; GPOPS-II example";
  p.hamiltonian_note =
      "not applicable: free final time and state bounds (H is linear in u: singular arc)";
  p.tags = {"singular-arc", "free-time", "control-constrained", "mayer"};
  return p;
}

}  // namespace ocpb
