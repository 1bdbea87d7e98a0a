#include "problems/registry.h"

#include <stdexcept>

#include "core/named_registry.h"

#include "problems/channel_sample.h"
#include "problems/comm_fixed_path.h"
#include "problems/comm_path2d.h"
#include "problems/comm_true_energy.h"
#include "problems/double_integrator.h"
#include "problems/reference/reference_problems.h"

namespace ocpb {
namespace {

std::vector<ProblemInfo> BuildRegistry() {
  std::vector<ProblemInfo> list;
  {
    ProblemInfo p;
    p.name = "double-integrator";
    p.description = "minimum-energy double integrator, x'' = u, 1/2 int u^2, fixed endpoints";
    p.parameters = DoubleIntegrator::ParameterSpecs(1e300);
    p.make = [](const Parameters& params, std::uint64_t) {
      return std::make_unique<DoubleIntegrator>(params, "double-integrator");
    };
    p.default_intervals = 100;
    p.reference_value = 6.0;
    p.reference_source =
        "analytic: u* = 6 - 12t (Bryson-Ho; CTProblems.jl double_integrator_energy)";
    // p1' = 0, p2' = -p1 and u* = -p2 = 6 - 12t give p* = (-12, 12t - 6).
    p.reference_costate = [](double t) { return Vec(Eigen::Vector2d(-12.0, 12.0 * t - 6.0)); };
    list.push_back(p);
  }
  {
    ProblemInfo p;
    p.name = "double-integrator-bounded";
    p.description = "double integrator with |u| <= 5";
    p.parameters = DoubleIntegrator::ParameterSpecs(5.0);
    p.make = [](const Parameters& params, std::uint64_t) {
      return std::make_unique<DoubleIntegrator>(params, "double-integrator-bounded");
    };
    p.default_intervals = 100;
    p.reference_value = 6.0450277563;
    p.reference_source = "CTProblems.jl double_integrator_energy_control_constraint";
    list.push_back(p);
  }
  // [problems] one block per problem, in the order `ocpbench list problems` prints them.
  AppendReferenceProblems(&list);  // bryson-denham, lqr, hager, vanderpol, rayleigh, catmix
  list.push_back(CommPath2dProblemInfo());
  list.back().sample_for_figures = SampleCommPath2dChannel;
  list.back().judge_on_truth = JudgeCommPlanOnTruth;
  list.push_back(CommFixedPathProblemInfo());
  list.back().judge_on_truth = JudgeCommPlanOnTruth;
  return list;
}

NamedRegistry<ProblemInfo>& Registry() {
  static NamedRegistry<ProblemInfo> registry("problem", BuildRegistry);
  return registry;
}

}  // namespace

const std::vector<ProblemInfo>& Problems() { return Registry().All(); }

void RegisterProblem(ProblemInfo info) {
  Registry().Add("RegisterProblem", std::move(info), [](const ProblemInfo& p) {
    if (!p.make)
      throw std::invalid_argument("RegisterProblem: '" + p.name + "' has no make function");
  });
}

const ProblemInfo& FindProblem(const std::string& name) { return Registry().Find(name); }

std::unique_ptr<Ocp> MakeProblem(const std::string& name,
                                 const std::vector<std::string>& assignments,
                                 std::uint64_t seed,
                                 Parameters* resolved) {
  const ProblemInfo& info = FindProblem(name);
  Parameters params(info.parameters);
  for (const std::string& a : assignments) params.SetFromString(a);
  auto ocp = info.make(params, seed);
  if (resolved) *resolved = params;
  return ocp;
}

}  // namespace ocpb
