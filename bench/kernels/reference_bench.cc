// Speed on the reference problems: Bryson-Denham with Hermite-Simpson at 50 intervals and Ipopt's
// exact Hessian, with the CPU time split into setup (transcription), derivative evaluation (every
// NLP callback, timed here) and Ipopt's own work; then every reference problem at the same
// setting. Numbers and commands: results/references/README.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>

#include "core/evaluator.h"
#include "core/timer.h"
#include "problems/registry.h"
#include "solvers/ipopt_adapter.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

// An Nlp that forwards to another and accumulates the CPU time spent in each kind of callback.
class TimedNlp final : public Nlp {
 public:
  struct Times {
    double objective = 0.0;    // f and grad f
    double constraints = 0.0;  // g
    double jacobian = 0.0;     // values of dg/dz
    double hessian = 0.0;      // values of the Hessian of the Lagrangian
    int calls = 0;
    double total() const { return objective + constraints + jacobian + hessian; }
  };

  explicit TimedNlp(const Nlp& inner) : inner_(inner) {
    jac_rows_ = inner.jacobian_rows();
    jac_cols_ = inner.jacobian_cols();
    hess_rows_ = inner.hessian_rows();
    hess_cols_ = inner.hessian_cols();
  }
  const Times& times() const { return times_; }

  int num_variables() const override { return inner_.num_variables(); }
  int num_constraints() const override { return inner_.num_constraints(); }
  void Bounds(Vec* zl, Vec* zu, Vec* gl, Vec* gu) const override { inner_.Bounds(zl, zu, gl, gu); }
  Vec StartingPoint() const override { return inner_.StartingPoint(); }
  bool Objective(ConstVecRef z, double* f) const override {
    return Timed(&times_.objective, [&] { return inner_.Objective(z, f); });
  }
  bool Gradient(ConstVecRef z, VecRef grad) const override {
    return Timed(&times_.objective, [&] { return inner_.Gradient(z, grad); });
  }
  bool Constraints(ConstVecRef z, VecRef g) const override {
    return Timed(&times_.constraints, [&] { return inner_.Constraints(z, g); });
  }
  bool JacobianValues(ConstVecRef z, VecRef values) const override {
    return Timed(&times_.jacobian, [&] { return inner_.JacobianValues(z, values); });
  }
  bool HasHessian() const override { return inner_.HasHessian(); }
  bool HessianValues(ConstVecRef z,
                     double sigma,
                     ConstVecRef lambda,
                     VecRef values) const override {
    return Timed(&times_.hessian, [&] { return inner_.HessianValues(z, sigma, lambda, values); });
  }

 private:
  template <class F>
  bool Timed(double* slot, F&& call) const {
    const double start = CpuSeconds();
    const bool ok = call();
    *slot += CpuSeconds() - start;
    ++times_.calls;
    return ok;
  }
  const Nlp& inner_;
  mutable Times times_;  // benchmark instrumentation; one solve at a time
};

// Bryson-Denham (J* = 4), Hermite-Simpson, N = 50, hard terminal form, Ipopt with the exact
// Hessian (MUMPS, tol 1e-8). Per solve: setup = transcription (building the sparse structure and
// the starting point), derivatives = every NLP callback (values, gradients, Jacobians, Hessians),
// ipopt = the rest of Ipopt's solve (linear algebra, line search, bookkeeping). Times are CPU
// seconds, averaged over the benchmark's iterations.
void BM_BrysonDenhamHermiteSimpson50(benchmark::State& state) {
  const auto ocp = MakeProblem("bryson-denham", {}, 0);
  TranscriptionOptions topt;
  topt.grid = TimeGrid::Uniform(0.0, 1.0, 50);
  topt.terminal = TerminalMode::kHard;
  const auto transcription = FindTranscription("hermite-simpson").make();
  IpoptOptions iopt;
  iopt.hessian_approximation = "exact";
  double setup = 0.0, derivatives = 0.0, ipopt = 0.0;
  double f_time = 0.0, g_time = 0.0, jac_time = 0.0, h_time = 0.0;
  int iterations = 0, calls = 0;
  NlpSolution last;
  double jbar_fine = NAN;
  for (auto _ : state) {
    const double t0 = CpuSeconds();
    const std::unique_ptr<TranscribedNlp> nlp = transcription->Transcribe(*ocp, topt);
    const Vec z0 = nlp->StartingPoint();
    const double t1 = CpuSeconds();
    const TimedNlp timed(*nlp);
    last = SolveNlpWithIpopt(timed, z0, iopt);
    const double t2 = CpuSeconds();
    setup += t1 - t0;
    derivatives += timed.times().total();
    ipopt += (t2 - t1) - timed.times().total();
    f_time += timed.times().objective;
    g_time += timed.times().constraints;
    jac_time += timed.times().jacobian;
    h_time += timed.times().hessian;
    iterations = last.iterations;
    calls = timed.times().calls;
    if (!IsSuccess(last.status)) {
      state.SkipWithError(("Ipopt: " + last.solver_status).c_str());
      return;
    }
    state.PauseTiming();
    jbar_fine = Evaluate(*ocp, nlp->Controls(last.z), topt.grid.Refined(10), Integrator::kRk4).Jbar;
    state.ResumeTiming();
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["setup_ms"] = 1e3 * setup / n;
  state.counters["derivatives_ms"] = 1e3 * derivatives / n;
  state.counters["ipopt_ms"] = 1e3 * ipopt / n;
  state.counters["total_ms"] = 1e3 * (setup + derivatives + ipopt) / n;
  state.counters["f_grad_ms"] = 1e3 * f_time / n;
  state.counters["g_ms"] = 1e3 * g_time / n;
  state.counters["jac_ms"] = 1e3 * jac_time / n;
  state.counters["hess_ms"] = 1e3 * h_time / n;
  state.counters["callbacks"] = calls;
  state.counters["iterations"] = iterations;
  state.counters["rel_error_objective"] = std::abs(last.objective - 4.0) / 4.0;
  state.counters["rel_error_fine"] = std::abs(jbar_fine - 4.0) / 4.0;
  state.SetLabel(last.solver_status);
}
BENCHMARK(BM_BrysonDenhamHermiteSimpson50)->Unit(benchmark::kMillisecond);

// The same solve through the registry (what `ocpbench solve` does): transcription, Ipopt, and
// the SolveResult (controls, states, multiplier-based costates).
void BM_BrysonDenhamIpoptSolve(benchmark::State& state) {
  const auto ocp = MakeProblem("bryson-denham", {}, 0);
  SolveRequest request;
  request.grid = TimeGrid::Uniform(0.0, 1.0, 50);
  request.terminal = TerminalMode::kHard;
  request.transcription = "hermite-simpson";
  const auto solver = FindSolver("ipopt").make();
  SolveResult r;
  for (auto _ : state) {
    r = solver->Solve(*ocp, request);
    if (!IsSuccess(r.status)) {
      state.SkipWithError(("Ipopt: " + r.solver_status).c_str());
      return;
    }
  }
  state.counters["iterations"] = r.iterations;
  state.counters["solve_cpu_ms"] = 1e3 * r.cpu_seconds;
  state.counters["ipopt_cpu_ms"] = 1e3 * r.solver_stats["ipopt_cpu_seconds"];
  state.SetLabel(r.solver_status);
}
BENCHMARK(BM_BrysonDenhamIpoptSolve)->Unit(benchmark::kMillisecond);

// Every reference problem: Ipopt on Hermite-Simpson at N = 50 (hard form), and the Hamiltonian
// descent on forward Euler at N = 100 (penalty form, its reformulation, 500 steps at most).
const char* const kProblems[] = {
    "bryson-denham", "lqr", "hager", "vanderpol", "rayleigh", "catmix"};

void ReportAgainstReference(
    benchmark::State& state, const Ocp& ocp, const std::string& name, const SolveResult& r, int N) {
  const double ref = *FindProblem(name).reference_value;
  const double jbar =
      Evaluate(
          ocp, r.controls, TimeGrid::Uniform(ocp.t0(), ocp.tf(), N).Refined(10), Integrator::kRk4)
          .Jbar;
  state.counters["iterations"] = r.iterations;
  state.counters["rel_error_fine"] = std::abs(jbar - ref) / std::abs(ref);
  state.counters["solve_cpu_ms"] = 1e3 * r.cpu_seconds;
  state.SetLabel(name + ": " + r.solver_status);
}

void BM_ReferenceIpoptHermiteSimpson50(benchmark::State& state) {
  const std::string name = kProblems[state.range(0)];
  const auto ocp = MakeProblem(name, {}, 0);
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 50);
  request.terminal = TerminalMode::kHard;
  request.transcription = "hermite-simpson";
  const auto solver = FindSolver("ipopt").make();
  SolveResult r;
  for (auto _ : state) r = solver->Solve(*ocp, request);
  ReportAgainstReference(state, *ocp, name, r, 50);
}
BENCHMARK(BM_ReferenceIpoptHermiteSimpson50)->DenseRange(0, 5)->Unit(benchmark::kMillisecond);

void BM_ReferenceHamiltonianEuler100(benchmark::State& state) {
  const std::string name = kProblems[state.range(0)];
  const auto ocp = MakeProblem(name, {}, 0);
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 100);
  request.terminal = TerminalMode::kPenalty;
  request.options = {{"theta_tolerance", "1e-10"}};
  const auto solver = FindSolver("hamiltonian").make();
  SolveResult r;
  for (auto _ : state) r = solver->Solve(*ocp, request);
  ReportAgainstReference(state, *ocp, name, r, 100);
}
BENCHMARK(BM_ReferenceHamiltonianEuler100)->DenseRange(0, 5)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ocpb
