// The NLP solvers on OCPBench problems: Ipopt per transcription, Ipopt's growth with N on
// Hermite-Simpson, Ipopt against the Hamiltonian descent on the paper's Euler grid, the hard
// terminal form, and where NLopt's dense algorithms stop being practical. Results and commands:
// solvers/README-nlp.md.
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/evaluator.h"
#include "problems/registry.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

const char* const kTranscriptions[] = {
    "euler", "trapezoid", "hermite-simpson", "lgr", "single-shooting"};

// The paper's problem with the registry's defaults (the predicted channel), seed 1. Returns null
// and marks the benchmark skipped when it cannot be built.
std::unique_ptr<Ocp> PaperProblem(benchmark::State& state,
                                  const std::vector<std::string>& settings = {}) {
  try {
    return MakeProblem("comm-path2d", settings, 1);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return nullptr;
  }
}

SolveRequest Request(const Ocp& ocp, const std::string& transcription, int N, TerminalMode mode) {
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  request.terminal = mode;
  request.transcription = transcription;
  return request;
}

// Counters every NLP benchmark reports, from the last run: the solver's status, iterations, its
// objective, and the common evaluator's J, Jbar and terminal violation on the request's grid
// (Euler: the discrete problem of the paper).
void Report(benchmark::State& state,
            const Ocp& ocp,
            const SolveRequest& request,
            const SolveResult& r) {
  const Evaluation ev = Evaluate(ocp, r.controls, request.grid, Integrator::kEuler);
  state.counters["success"] = IsSuccess(r.status) ? 1 : 0;
  state.counters["iterations"] = r.iterations;
  state.counters["objective"] = r.objective;
  state.counters["J_euler"] = ev.J;
  state.counters["Jbar_euler"] = ev.Jbar;
  state.counters["terminal_violation"] = ev.terminal_violation;
  state.counters["solver_cpu_s"] = r.cpu_seconds;
  if (r.iterations > 0) state.counters["cpu_s_per_iteration"] = r.cpu_seconds / r.iterations;
  state.SetLabel(r.solver_status);
}

// ---- Ipopt on the double integrator, each transcription (hard form, J* = 6) ------------------

void BM_IpoptDoubleIntegrator(benchmark::State& state) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const std::string transcription = kTranscriptions[state.range(0)];
  const SolveRequest request =
      Request(*ocp, transcription, static_cast<int>(state.range(1)), TerminalMode::kHard);
  const auto solver = FindSolver("ipopt").make();
  SolveResult r;
  for (auto _ : state) r = solver->Solve(*ocp, request);
  Report(state, *ocp, request, r);
  state.SetLabel(transcription + " " + r.solver_status);
}
BENCHMARK(BM_IpoptDoubleIntegrator)
    ->ArgNames({"scheme", "N"})
    ->ArgsProduct({{0, 1, 2, 3, 4}, {100, 1000}})
    ->Unit(benchmark::kMillisecond);

// ---- Ipopt on the paper's problem, each transcription, N = 400 (dt = 0.1 s) -------------------

void BM_IpoptPaperProblem(benchmark::State& state) {
  const auto ocp = PaperProblem(state);
  if (!ocp) return;
  const std::string transcription = kTranscriptions[state.range(0)];
  const TerminalMode mode = state.range(1) == 0 ? TerminalMode::kPenalty : TerminalMode::kHard;
  const SolveRequest request = Request(*ocp, transcription, 400, mode);
  const auto solver = FindSolver("ipopt").make();
  SolveResult r;
  for (auto _ : state) r = solver->Solve(*ocp, request);
  Report(state, *ocp, request, r);
  state.SetLabel(transcription + " " + ToString(mode) + " " + r.solver_status);
}
BENCHMARK(BM_IpoptPaperProblem)
    ->ArgNames({"scheme", "hard"})
    ->ArgsProduct({{0, 1, 2, 3}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// ---- Ipopt's growth with N: Hermite-Simpson on the paper's problem ------------------------------
// The KKT matrix of a collocation NLP is banded (block size ~ 2 nx + nu), so MUMPS's work per
// iteration should grow about linearly in N; Complexity() fits the total time.

void BM_IpoptHermiteSimpsonScaling(benchmark::State& state) {
  const auto ocp = PaperProblem(state);
  if (!ocp) return;
  const int N = static_cast<int>(state.range(0));
  const SolveRequest request = Request(*ocp, "hermite-simpson", N, TerminalMode::kPenalty);
  const auto solver = FindSolver("ipopt").make();
  SolveResult r;
  for (auto _ : state) r = solver->Solve(*ocp, request);
  Report(state, *ocp, request, r);
  state.SetComplexityN(N);
}
BENCHMARK(BM_IpoptHermiteSimpsonScaling)
    ->ArgName("N")
    ->Arg(100)
    ->Arg(300)
    ->Arg(1000)
    ->Arg(3000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Complexity();

// ---- Ipopt against the Hamiltonian descent: the paper's problem, Euler, penalty, N = 400 ----
// Same discrete problem (DiscreteOcp with Euler), same start (u = 0 projected onto U). Reports
// both final J and the CPU time each history needs to come within 1% of the better final J.

// The first CPU time at which the history's J is <= target, counting for an NLP solver only
// iterates whose constraint violation (Ipopt's inf_pr: here the Euler defects) is <= 1e-6, so
// that an infeasible iterate cannot "reach" a cost its controls do not have.
double CpuToWithin(const SolveResult& r, double target) {
  for (const IterationRecord& rec : r.history) {
    const bool feasible = std::isnan(rec.primal_inf) || rec.primal_inf <= 1e-6;
    if (std::isfinite(rec.J) && rec.J <= target && feasible) return rec.cpu_seconds;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

void BM_PaperEulerIpoptVersusHamiltonian(benchmark::State& state) {
  const auto ocp = PaperProblem(state);
  if (!ocp) return;
  const SolveRequest request = Request(*ocp, "euler", 400, TerminalMode::kPenalty);
  SolveResult ipopt, hamiltonian;
  for (auto _ : state) {
    ipopt = FindSolver("ipopt").make()->Solve(*ocp, request);
    hamiltonian = FindSolver("hamiltonian").make()->Solve(*ocp, request);
  }
  // Judge both by the common evaluator (the same Euler cost on the same grid).
  const double J_ipopt = Evaluate(*ocp, ipopt.controls, request.grid, Integrator::kEuler).J;
  const double J_ham = Evaluate(*ocp, hamiltonian.controls, request.grid, Integrator::kEuler).J;
  const double best = std::min(J_ipopt, J_ham);
  state.counters["J_ipopt"] = J_ipopt;
  state.counters["J_hamiltonian"] = J_ham;
  state.counters["cpu_s_ipopt"] = ipopt.cpu_seconds;
  state.counters["cpu_s_hamiltonian"] = hamiltonian.cpu_seconds;
  state.counters["cpu_s_to_1pct_ipopt"] = CpuToWithin(ipopt, 1.01 * best);
  state.counters["cpu_s_to_1pct_hamiltonian"] = CpuToWithin(hamiltonian, 1.01 * best);
  state.counters["iterations_ipopt"] = ipopt.iterations;
  state.counters["iterations_hamiltonian"] = hamiltonian.iterations;
  state.SetLabel("ipopt " + ipopt.solver_status + ", hamiltonian " + hamiltonian.solver_status);
}
BENCHMARK(BM_PaperEulerIpoptVersusHamiltonian)->Unit(benchmark::kMillisecond)->Iterations(1);

// ---- The hard terminal form on the paper's problem ---------------------------------------------
// psi(x(tf)) = 0 enforced; the terminal residual must reach <= 1e-6. Jbar (no penalty) is
// compared with the penalty solution's on the same grid and scheme.

void BM_PaperHardTerminal(benchmark::State& state) {
  const auto ocp = PaperProblem(state);
  if (!ocp) return;
  const std::string transcription = kTranscriptions[state.range(0)];
  const SolveRequest hard = Request(*ocp, transcription, 400, TerminalMode::kHard);
  const SolveRequest penalty = Request(*ocp, transcription, 400, TerminalMode::kPenalty);
  const auto solver = FindSolver("ipopt").make();
  SolveResult r_hard, r_penalty;
  for (auto _ : state) r_hard = solver->Solve(*ocp, hard);
  r_penalty = solver->Solve(*ocp, penalty);
  // The scheme's own terminal residual (NLP constraint violation) and the evaluator's on a fine
  // RK4 grid (collocation controls re-simulated).
  const Evaluation fine_hard =
      Evaluate(*ocp, r_hard.controls, hard.grid.Refined(10), Integrator::kRk4);
  const Evaluation fine_penalty =
      Evaluate(*ocp, r_penalty.controls, hard.grid.Refined(10), Integrator::kRk4);
  state.counters["success"] = IsSuccess(r_hard.status) ? 1 : 0;
  state.counters["iterations"] = r_hard.iterations;
  state.counters["nlp_violation"] =
      r_hard.solver_stats.count("nlp_violation") ? r_hard.solver_stats.at("nlp_violation") : NAN;
  state.counters["Jbar_hard"] = r_hard.objective;
  state.counters["Jbar_penalty_rk4"] = fine_penalty.Jbar;
  state.counters["Jbar_hard_rk4"] = fine_hard.Jbar;
  state.counters["terminal_violation_hard_rk4"] = fine_hard.terminal_violation;
  state.counters["terminal_violation_penalty_rk4"] = fine_penalty.terminal_violation;
  state.SetLabel(transcription + " hard " + r_hard.solver_status + ", penalty " +
                 r_penalty.solver_status);
}
BENCHMARK(BM_PaperHardTerminal)
    ->ArgName("scheme")
    ->DenseRange(0, 3)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// ---- NLopt's dense algorithms against N: single shooting on the paper's problem ----------------
// n = 3N controls, N ball rows (|u| <= umax). Ipopt on the Euler transcription gives the
// reference J of the same discrete problem; "rel_gap" is (J - J_ipopt) / J_ipopt.

// Peak resident memory of one benchmark case. Freed heap that glibc kept from earlier cases is
// first returned to the system (malloc_trim), so the resident size at the start is the live
// baseline. Linux lets a process reset its resident-set high-water mark (write "5" to
// /proc/self/clear_refs, Linux >= 4.0); VmHWM in /proc/self/status is then the peak since the
// reset, so every case gets its own peak even after a larger one ran in the same process. Where
// the reset is refused, the rise of getrusage's ru_maxrss is reported instead: a lower bound (0
// when an earlier case peaked higher), flagged by peak_reset = 0.
class PeakMemory {
 public:
  PeakMemory() {
    malloc_trim(0);
    std::ofstream clear("/proc/self/clear_refs");
    reset_ = static_cast<bool>(clear << "5" << std::flush);
    before_mb_ = StatusMb("VmRSS:");
    maxrss_before_mb_ = MaxRssMb();
  }
  bool reset() const { return reset_; }
  double before_mb() const { return before_mb_; }
  // The peak resident memory since construction, in MB.
  double peak_mb() const {
    if (reset_) return StatusMb("VmHWM:");
    return before_mb_ + std::max(0.0, MaxRssMb() - maxrss_before_mb_);
  }

 private:
  static double StatusMb(const std::string& key) {
    std::ifstream status("/proc/self/status");
    std::string word;
    while (status >> word) {
      if (word == key) {
        double kb = NAN;
        status >> kb;
        return kb / 1024.0;
      }
    }
    return NAN;
  }
  static double MaxRssMb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) / 1024.0;  // kB on Linux
  }
  bool reset_ = false;
  double before_mb_ = NAN, maxrss_before_mb_ = NAN;
};

const char* const kNloptAlgorithms[] = {"LD_SLSQP", "LD_MMA", "LD_CCSAQ", "AUGLAG"};

// Each run is capped at `maxtime` seconds of wall time (NLopt checks it between evaluations, so
// one SLSQP iteration can overrun it): time per evaluation and memory are measured at every N,
// convergence where it comes within the cap. The refusal limits are lifted.
void BM_NloptSingleShootingScaling(benchmark::State& state) {
  const auto ocp = PaperProblem(state);
  if (!ocp) return;
  const int N = static_cast<int>(state.range(1));
  SolveRequest request = Request(*ocp, "single-shooting", N, TerminalMode::kPenalty);
  request.options.Set("algorithm", kNloptAlgorithms[state.range(0)]);
  request.options = {{"maxtime", std::to_string(state.range(2))},
                     {"slsqp_max_variables", "100000"},
                     {"mma_max_inequalities", "100000"},
                     {"max_dense_jacobian", "1e12"}};
  const auto solver = FindSolver("nlopt").make();
  SolveResult r;
  double peak_mb = NAN, before_mb = NAN;
  bool reset = false;
  for (auto _ : state) {
    const PeakMemory memory;
    r = solver->Solve(*ocp, request);
    peak_mb = memory.peak_mb();
    before_mb = memory.before_mb();
    reset = memory.reset();
  }
  SolveRequest reference = Request(*ocp, "euler", N, TerminalMode::kPenalty);
  const SolveResult ipopt = FindSolver("ipopt").make()->Solve(*ocp, reference);
  Report(state, *ocp, request, r);
  state.counters["n"] = 3.0 * N;
  state.counters["evaluations"] = r.iterations;
  state.counters["rel_gap"] = (r.objective - ipopt.objective) / std::abs(ipopt.objective);
  state.counters["peak_rss_MB"] = peak_mb;
  state.counters["peak_rise_MB"] = peak_mb - before_mb;
  state.counters["peak_reset"] = reset ? 1 : 0;
  state.SetLabel(std::string(kNloptAlgorithms[state.range(0)]) + " " + r.solver_status);
}

// (algorithm, N, maxtime s): each algorithm up to the N where one run still fits a few seconds
// (solvers/README-nlp.md, "NLopt: where each algorithm stops being practical").
void NloptScalingArgs(benchmark::internal::Benchmark* b) {
  const int cap = 5;
  for (int N : {25, 50, 100, 200, 400}) b->Args({0, N, cap});  // LD_SLSQP
  for (int alg : {1, 2}) {
    for (int N : {25, 50, 100, 200, 400, 800}) b->Args({alg, N, cap});  // LD_MMA, LD_CCSAQ
  }
  for (int N : {25, 50, 100, 200, 400, 800, 1600, 2400}) b->Args({3, N, cap});  // AUGLAG
}
BENCHMARK(BM_NloptSingleShootingScaling)
    ->ArgNames({"alg", "N", "maxtime"})
    ->Apply(NloptScalingArgs)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace
}  // namespace ocpb
