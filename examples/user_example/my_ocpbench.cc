// A complete `ocpbench` with this project's problem and solver beside the built-in ones:
//
//   my_ocpbench list solvers                          (... projected-gradient)
//   my_ocpbench describe solver projected-gradient    (its options, defaults and rules)
//   my_ocpbench run my_suite.json --out results/mine  (records, summary.md, records.csv)
//
// OCPBench's command line is the library target OCPBench::cli; ocpb::Main runs it.
#include "bench/cli/main.h"
#include "my_lq_problem.h"
#include "my_solver.h"
#include "problems/registry.h"
#include "solvers/registry.h"

int main(int argc, char** argv) {
  ocpb::RegisterProblem(my_project::MyLqProblemInfo());
  ocpb::RegisterSolver(my_project::ProjectedGradient::Info());
  return ocpb::Main(argc, argv);
}
