#include "problems/registry.h"

#include <stdexcept>

#include "problems/comm_fixed_path.h"
#include "problems/comm_path2d.h"
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
    p.reference_source = "analytic: u* = 6 - 12t (Bryson-Ho; CTProblems.jl double_integrator_energy)";
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
  list.push_back(CommFixedPathProblemInfo());
  return list;
}

std::vector<ProblemInfo>& MutableProblems() {
  static std::vector<ProblemInfo> registry = BuildRegistry();
  return registry;
}

}  // namespace

const std::vector<ProblemInfo>& Problems() { return MutableProblems(); }

void RegisterProblem(ProblemInfo info) {
  if (info.name.empty()) throw std::invalid_argument("RegisterProblem: the name must not be empty");
  if (!info.make) {
    throw std::invalid_argument("RegisterProblem: '" + info.name + "' has no make function");
  }
  for (const ProblemInfo& p : MutableProblems()) {
    if (p.name == info.name) {
      throw std::invalid_argument("RegisterProblem: a problem named '" + info.name +
                                  "' exists already");
    }
  }
  MutableProblems().push_back(std::move(info));
}

const ProblemInfo& FindProblem(const std::string& name) {
  std::string names;
  for (const ProblemInfo& p : Problems()) {
    if (p.name == name) return p;
    names += (names.empty() ? "" : ", ") + p.name;
  }
  throw std::invalid_argument("unknown problem '" + name + "' (valid: " + names + ")");
}

std::unique_ptr<Ocp> MakeProblem(const std::string& name, const std::vector<std::string>& assignments,
                                 std::uint64_t seed, Parameters* resolved) {
  const ProblemInfo& info = FindProblem(name);
  Parameters params(info.parameters);
  for (const std::string& a : assignments) params.SetFromString(a);
  auto ocp = info.make(params, seed);
  if (resolved) *resolved = params;
  return ocp;
}

}  // namespace ocpb
