// Derivative kernels of the direct transcriptions: one evaluation of the constraint Jacobian and
// one of the Hessian of the Lagrangian (exact, sparse) per transcription at N = 400, on the double
// integrator and on the paper's problem (comm-path2d, once registered).
//
//   ocpbench_kernels --benchmark_filter=Transcription
//
// Arguments: N, part (0 = Jacobian, 1 = Hessian). Counters: n (variables), m (constraints),
// nnz (triplets of the part). The NLP is built once, outside the timed region; the point is the
// transcription's starting point, the multipliers all 0.1.
#include <map>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "problems/registry.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

// Problems built once per process; nullptr (with the reason) when the name is not registered.
const Ocp* CachedProblem(const std::string& name, std::string* error) {
  static std::map<std::string, std::unique_ptr<Ocp>> cache;
  static std::map<std::string, std::string> failures;
  if (!cache.count(name) && !failures.count(name)) {
    try {
      cache[name] = MakeProblem(name, {}, 1);
    } catch (const std::exception& e) {
      failures[name] = e.what();
    }
  }
  if (failures.count(name)) {
    *error = failures[name];
    return nullptr;
  }
  return cache[name].get();
}

void BM_TranscriptionDerivatives(benchmark::State& state,
                                 const std::string& problem,
                                 const std::string& scheme) {
  std::string error;
  const Ocp* ocp = CachedProblem(problem, &error);
  if (!ocp) {
    state.SkipWithError(error.c_str());
    return;
  }
  TranscriptionOptions options;
  options.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), static_cast<int>(state.range(0)));
  options.terminal = TerminalMode::kHard;
  const auto nlp = FindTranscription(scheme).make()->Transcribe(*ocp, options);
  const Vec z = nlp->StartingPoint();
  const Vec lambda = Vec::Constant(nlp->num_constraints(), 0.1);
  const bool hessian = state.range(1) == 1;
  Vec values(hessian ? nlp->hessian_rows().size() : nlp->jacobian_rows().size());
  for (auto _ : state) {
    const bool ok =
        hessian ? nlp->HessianValues(z, 1.0, lambda, values) : nlp->JacobianValues(z, values);
    benchmark::DoNotOptimize(ok);
    benchmark::DoNotOptimize(values.data());
  }
  state.counters["n"] = nlp->num_variables();
  state.counters["m"] = nlp->num_constraints();
  state.counters["nnz"] = static_cast<double>(values.size());
}

#define OCPB_TRANSCRIPTION_BENCH(label, problem, scheme)                                           \
  BENCHMARK_CAPTURE(BM_TranscriptionDerivatives, label, std::string(problem), std::string(scheme)) \
      ->ArgNames({"N", "hessian"})                                                                 \
      ->ArgsProduct({{400}, {0, 1}})                                                               \
      ->Unit(benchmark::kMicrosecond)

OCPB_TRANSCRIPTION_BENCH(di_euler, "double-integrator", "euler");
OCPB_TRANSCRIPTION_BENCH(di_trapezoid, "double-integrator", "trapezoid");
OCPB_TRANSCRIPTION_BENCH(di_hermite_simpson, "double-integrator", "hermite-simpson");
OCPB_TRANSCRIPTION_BENCH(di_lgr3, "double-integrator", "lgr");
OCPB_TRANSCRIPTION_BENCH(comm_path2d_euler, "comm-path2d", "euler");
OCPB_TRANSCRIPTION_BENCH(comm_path2d_trapezoid, "comm-path2d", "trapezoid");
OCPB_TRANSCRIPTION_BENCH(comm_path2d_hermite_simpson, "comm-path2d", "hermite-simpson");
OCPB_TRANSCRIPTION_BENCH(comm_path2d_lgr3, "comm-path2d", "lgr");

}  // namespace
}  // namespace ocpb
