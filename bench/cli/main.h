// OCPBench's command line as a library entry point (the gtest_main / benchmark_main
// convention): a program that registers its own problems and solvers and then calls
// ocpb::Main is a complete `ocpbench` (list, describe, solve, run, merge, channel, online),
// with the registered entries beside the built-in ones. See examples/user_example/.
#pragma once

namespace ocpb {

/// Runs the `ocpbench` command line on argv and returns the process exit code (0 ok, 1 some
/// case failed, 2 invalid input, 3 internal error). Every error is one line "ocpbench: error:
/// ..." on stderr. Register problems (RegisterProblem), solvers (RegisterSolver) and
/// transcriptions (RegisterTranscription) before calling it.
int Main(int argc, char** argv);

}  // namespace ocpb
