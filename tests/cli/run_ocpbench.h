// Runs the ocpbench program as a user would, capturing stdout, stderr and the exit code.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace ocpb::testing {

struct ProgramRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

/// Runs `ocpbench args...` in directory `cwd` (empty: the current one).
ProgramRun RunOcpbenchProgram(const std::vector<std::string>& args, const std::string& cwd = "");

/// Starts `ocpbench args...` in the background; returns its pid.
int StartOcpbenchProgram(const std::vector<std::string>& args, const std::string& cwd);

/// A fresh empty directory under the test's temporary directory.
std::string FreshDirectory(const std::string& name);

/// True when the run's stderr is exactly one line "ocpbench: error: ..." (the contract for
/// refused input).
bool OneErrorLine(const ProgramRun& run);

/// Every regular file under `dir` (relative path -> text), links and the lock file left out:
/// what a refused command must leave unchanged.
std::map<std::string, std::string> SnapshotFiles(const std::string& dir);

/// `a` followed by `b`: a command line with more arguments.
std::vector<std::string> Plus(std::vector<std::string> a, const std::vector<std::string>& b);

/// A solve that ends in well under a second under the sanitizers: Ipopt on the double
/// integrator, Euler, N = 10.
const std::vector<std::string>& QuickIpoptSolve();

void WriteText(const std::string& path, const std::string& text);
std::string ReadText(const std::string& path);

}  // namespace ocpb::testing
