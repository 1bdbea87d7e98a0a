#include "solvers/registry.h"

#include <stdexcept>

#include "core/named_registry.h"
#include "solvers/baseline_solver.h"
#include "solvers/hamiltonian_descent.h"
#include "solvers/hamiltonian_family.h"
#include "solvers/indirect_newton.h"
#include "solvers/ipopt_solver.h"
#include "solvers/nlopt_solver.h"
#include "solvers/riccati_ip_solver.h"

namespace ocpb {
namespace {

std::vector<SolverInfo> BuildSolvers() {
  std::vector<SolverInfo> list;
  // [solvers] one entry per solver, in the order `ocpbench list solvers` prints them.
  {
    SolverInfo s;
    s.name = "hamiltonian";
    s.description =
        "Hamiltonian-based descent with Armijo steps on the discrete penalized cost (Ali, Cai, "
        "Mostofi, Wardi, ACC 2016, Sec. II.C)";
    s.make = [] { return std::make_unique<HamiltonianDescent>(); };
    s.options = HamiltonianDescent::Schema();
    s.check_options = [](const OptionMap& resolved) { HamiltonianDescent::ApplyOptions(resolved); };
    // The paper's re-plans take "under 50 iterations" (Sec. IV).
    s.replan_defaults = {{"max_iterations", 50}};
    s.accuracy_option = "theta_tolerance";
    s.accuracy_note =
        "stops when |theta| <= theta_tolerance; 0 (the default) is off, so max_iterations or the "
        "Armijo limit ends the solve and bounds the accuracy";
    list.push_back(std::move(s));
  }
  // The Hamiltonian family (solvers/README-family.md): one solver, three presets.
  for (const auto preset : {HamiltonianFamily::Preset::kProximal,
                            HamiltonianFamily::Preset::kAugmentedLagrangian,
                            HamiltonianFamily::Preset::kPolish}) {
    SolverInfo s;
    s.name = HamiltonianFamily::Name(preset);
    s.description = HamiltonianFamily::Description(preset);
    s.make = [preset] { return std::make_unique<HamiltonianFamily>(preset); };
    s.options = HamiltonianFamily::Schema(preset);
    s.check_options = [preset](const OptionMap& resolved) {
      HamiltonianFamily::ApplyOptions(preset, resolved, HamiltonianFamily::Defaults(preset));
    };
    s.replan_defaults = {{"max_iterations", 50}};
    s.factorizes_sparse_matrices = preset == HamiltonianFamily::Preset::kPolish;
    list.push_back(std::move(s));
  }
  {
    SolverInfo s;
    s.name = "indirect-newton";
    s.description =
        "indirect method: semismooth Newton on the trapezoidal maximum-principle BVP (states, "
        "costates), sparse LU by UMFPACK/KLU; warm_start=hamiltonian polishes the descent";
    s.make = [] { return std::make_unique<IndirectNewton>(); };
    s.options = IndirectNewton::Schema();
    s.check_options = [](const OptionMap& resolved) { IndirectNewton::ApplyOptions(resolved); };
    s.factorizes_sparse_matrices = true;
    s.accuracy_option = "tolerance";
    s.accuracy_note =
        "converged when the discrete maximum principle's residual ||F||_inf <= tolerance: the "
        "trapezoidal BVP is then solved to that level, and the grid (O(h^2)) bounds the accuracy";
    list.push_back(std::move(s));
  }
  {
    SolverInfo s;
    s.name = "ipopt";
    s.description = "Ipopt 3.11 (interior point, MUMPS) on a transcription (--transcription)";
    s.make = [] { return std::make_unique<IpoptSolver>(); };
    s.uses_transcription = true;
    s.options = IpoptSolver::Schema();
    s.check_options = [](const OptionMap& resolved) { IpoptSolver::ApplyOptions(resolved); };
    // A warm start near the optimum: a small initial barrier parameter saves iterations
    // (online re-planning, seed 1: 8-12 instead of 11-14 per re-plan).
    s.replan_defaults = {{"mu_init", 1e-4}};
    s.factorizes_sparse_matrices = true;
    s.accuracy_option = "tol";
    s.accuracy_note =
        "stops when the scaled NLP error (dual infeasibility, constraint violation, "
        "complementarity) <= tol; at large N the discretization error falls below what tol "
        "resolves and tol, not the grid, limits the accuracy (brachistochrone-free-time, "
        "Hermite-Simpson, N = 1000: |T - T*| = 5.0e-6 at tol = 1e-8, 3.9e-9 at tol = 1e-12)";
    list.push_back(std::move(s));
  }
  {
    SolverInfo s;
    s.name = "riccati-ip";
    s.description =
        "primal-dual interior point (filter line search) whose Newton step is a stagewise "
        "Riccati recursion; euler and trapezoid transcriptions (solvers/README-riccati-ip.md)";
    s.make = [] { return std::make_unique<RiccatiIpSolver>(); };
    s.uses_transcription = true;
    s.options = RiccatiIpOptions::Schema();
    s.check_options = [](const OptionMap& resolved) {
      RiccatiIpOptions::Apply(resolved, RiccatiIpOptions());
    };
    s.accuracy_option = "tol";
    s.accuracy_note =
        "stops when Ipopt's scaled KKT error (dual infeasibility, constraint violation, "
        "complementarity) <= tol, with the objective scaled by Ipopt's gradient-based rule and "
        "the constraint rows unscaled";
    list.push_back(std::move(s));
  }
  {
    SolverInfo s;
    s.name = "nlopt";
    s.description =
        "NLopt 2.7 dense algorithms (LD_SLSQP, LD_MMA, LD_CCSAQ, LD_LBFGS, AUGLAG, AUGLAG_EQ) on a "
        "transcription; refuses sizes beyond its limits";
    s.make = [] { return std::make_unique<NloptSolver>(); };
    s.uses_transcription = true;
    s.options = NloptSolver::Schema();
    s.check_options = [](const OptionMap& resolved) { NloptSolver::ApplyOptions(resolved); };
    s.accuracy_option = "ftol_rel";
    s.accuracy_note =
        "stops when a step changes f by less than ftol_rel |f| (or x by xtol_rel); OCPBench "
        "then checks stationarity against stationarity_tol, which bounds the accuracy";
    list.push_back(std::move(s));
  }
  {
    SolverInfo s;
    s.name = "baseline";
    s.description =
        "the problem's own unoptimized plan (comm problems: constant speed along S-D or the given "
        "path, constant rate sending c bits by tf), evaluated like any method's answer";
    s.make = [] { return std::make_unique<BaselineSolver>(); };
    s.options = BaselineSolver::Schema();
    list.push_back(std::move(s));
  }
  return list;
}

NamedRegistry<SolverInfo>& Registry() {
  static NamedRegistry<SolverInfo> registry("solver", BuildSolvers);
  return registry;
}

}  // namespace

const std::vector<SolverInfo>& Solvers() { return Registry().All(); }

const SolverInfo& FindSolver(const std::string& name) { return Registry().Find(name); }

void RegisterSolver(SolverInfo info) {
  Registry().Add("RegisterSolver", std::move(info), [](const SolverInfo& s) {
    if (!s.make)
      throw std::invalid_argument("RegisterSolver: '" + s.name + "' has no make function");
  });
}

}  // namespace ocpb
