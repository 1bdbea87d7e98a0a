#include "problems/registry.h"

#include <stdexcept>

#include "core/named_registry.h"

#include "problems/channel_sample.h"
#include "problems/comm_fixed_path.h"
#include "problems/comm_path2d.h"
#include "problems/comm_true_energy.h"
#include "problems/double_integrator.h"
#include "problems/library/library_groups.h"
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
    p.tags = {"smooth"};
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
    p.tags = {"control-constrained"};
    list.push_back(p);
  }
  // [problems] one block per problem, in the order `ocpbench list problems` prints them.
  AppendReferenceProblems(&list);  // bryson-denham, lqr, hager, vanderpol, rayleigh, catmix
  list.push_back(CommPath2dProblemInfo());
  list.back().sample_for_figures = SampleCommPath2dChannel;
  list.back().judge_on_truth = JudgeCommPlanOnTruth;
  list.push_back(CommFixedPathProblemInfo());
  list.back().judge_on_truth = JudgeCommPlanOnTruth;
  // The library (issue 38): problems of the field's public suites, by the suite they come from.
  AppendCtbenchProblemsA(&list);
  AppendCtbenchProblemsB(&list);
  AppendClassicProblems(&list);
  return list;
}

NamedRegistry<ProblemInfo>& Registry() {
  static NamedRegistry<ProblemInfo> registry("problem", BuildRegistry);
  return registry;
}

}  // namespace

const std::vector<ProblemTag>& ProblemTags() {
  static const std::vector<ProblemTag> tags = {
      {"smooth", "smooth optimal control, no active bound or constraint arcs"},
      {"control-constrained", "bounds on the controls are active on part of the horizon"},
      {"bang-bang", "the optimal control switches between its bounds"},
      {"singular-arc", "a singular arc: H is linear in u and u* is not given by the bounds"},
      {"chattering", "infinitely many switches near a junction (Fuller's phenomenon)"},
      {"state-constrained", "a pure state constraint (path row or state bound) is active"},
      {"mixed-constraint", "a path constraint on states and controls together is active"},
      {"free-time", "the final time is a decision (free or minimized)"},
      {"free-initial-state", "some initial states are decisions"},
      {"boundary-constraints", "general constraints on x(t0) and x(tf) together"},
      {"static-parameters", "constant decision parameters besides the controls"},
      {"parameter-estimation", "fits model parameters to measurements"},
      {"multi-phase", "several phases joined by linkage conditions"},
      {"mayer", "the cost is a function of the end states only"},
      {"stiff", "the dynamics have widely separated time scales"},
      {"high-dimensional", "ten or more states, or many controls"},
      {"aerospace", "a flight, launch, reentry or orbit problem"},
      {"paper", "the problems of the paper OCPBench reproduces"},
  };
  return tags;
}

void CheckProblemTag(const std::string& where, const std::string& tag) {
  std::string names;
  for (const ProblemTag& t : ProblemTags()) {
    if (tag == t.name) return;
    names += (names.empty() ? "" : ", ") + std::string(t.name);
  }
  throw std::invalid_argument(where + ": unknown tag '" + tag + "' (the tags: " + names + ")");
}

const std::vector<ProblemInfo>& Problems() { return Registry().All(); }

void RegisterProblem(ProblemInfo info) {
  Registry().Add("RegisterProblem", std::move(info), [](const ProblemInfo& p) {
    if (!p.make)
      throw std::invalid_argument("RegisterProblem: '" + p.name + "' has no make function");
    for (const std::string& tag : p.tags) CheckProblemTag("RegisterProblem: '" + p.name + "'", tag);
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
