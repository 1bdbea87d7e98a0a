#include "solvers/registry.h"

#include <stdexcept>

#include "solvers/hamiltonian_descent.h"
#include "solvers/indirect_newton.h"
#include "solvers/ipopt_solver.h"
#include "solvers/nlopt_solver.h"
#include "transcriptions/single_shooting.h"
#include "transcriptions/euler.h"
#include "transcriptions/hermite_simpson.h"
#include "transcriptions/lgr.h"
#include "transcriptions/trapezoid.h"

namespace ocpb {
namespace {

std::vector<SolverInfo> BuildSolvers() {
  std::vector<SolverInfo> list;
  // [solvers] one push_back per solver, in the order `ocpbench list solvers` prints them.
  list.push_back({"hamiltonian",
                  "Hamiltonian-based descent with Armijo steps on the discrete penalized cost "
                  "(Ali, Cai, Mostofi, Wardi, ACC 2016, Sec. II.C)",
                  [] { return std::make_unique<HamiltonianDescent>(); },
                  false});
  list.push_back({"indirect-newton",
                  "indirect method: semismooth Newton on the trapezoidal maximum-principle BVP "
                  "(states, costates), sparse LU by UMFPACK/KLU; warm_start=hamiltonian polishes "
                  "the descent",
                  [] { return std::make_unique<IndirectNewton>(); },
                  false});
  list.push_back({"ipopt",
                  "Ipopt 3.11 (interior point, MUMPS) on a transcription (--transcription)",
                  [] { return std::make_unique<IpoptSolver>(); },
                  true});
  list.push_back({"nlopt",
                  "NLopt 2.7 dense algorithms (LD_SLSQP, LD_MMA, LD_CCSAQ, LD_LBFGS, AUGLAG, "
                  "AUGLAG_EQ) on a transcription; refuses sizes beyond its limits",
                  [] { return std::make_unique<NloptSolver>(); },
                  true});
  return list;
}

std::vector<TranscriptionInfo> BuildTranscriptions() {
  std::vector<TranscriptionInfo> list;
  // [transcriptions] one push_back per transcription.
  list.push_back({"euler",
                  "forward Euler: x_k and piecewise-constant u_k as variables, the Hamiltonian "
                  "descent's discrete problem (order 1)",
                  [] { return std::make_unique<EulerTranscription>(); }});
  list.push_back({"trapezoid",
                  "trapezoidal collocation, piecewise-linear controls (order 2)",
                  [] { return std::make_unique<TrapezoidTranscription>(); }});
  list.push_back({"hermite-simpson",
                  "Hermite-Simpson collocation, separated form, quadratic controls (order 4)",
                  [] { return std::make_unique<HermiteSimpsonTranscription>(); }});
  list.push_back({"lgr",
                  "Legendre-Gauss-Radau collocation, --degree points per interval (order 2K-1)",
                  [] { return std::make_unique<LgrTranscription>(); }});
  list.push_back({"single-shooting",
                  "controls only, piecewise constant; cost by forward Euler simulation, gradient "
                  "by the discrete adjoint (RK4 with --integrator rk4)",
                  [] { return std::make_unique<SingleShooting>(); }});
  return list;
}

template <class Info>
const Info& FindByName(const std::vector<Info>& list, const std::string& name, const char* what) {
  std::string names;
  for (const Info& i : list) {
    if (i.name == name) return i;
    names += (names.empty() ? "" : ", ") + i.name;
  }
  throw std::invalid_argument(std::string("unknown ") + what + " '" + name + "' (valid: " +
                              (names.empty() ? "none" : names) + ")");
}

}  // namespace

const std::vector<SolverInfo>& Solvers() {
  static const std::vector<SolverInfo> list = BuildSolvers();
  return list;
}

const std::vector<TranscriptionInfo>& Transcriptions() {
  static const std::vector<TranscriptionInfo> list = BuildTranscriptions();
  return list;
}

const SolverInfo& FindSolver(const std::string& name) { return FindByName(Solvers(), name, "solver"); }

const TranscriptionInfo& FindTranscription(const std::string& name) {
  return FindByName(Transcriptions(), name, "transcription");
}

}  // namespace ocpb
