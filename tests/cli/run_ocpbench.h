// Runs the ocpbench program as a user would, capturing stdout, stderr and the exit code.
#pragma once

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

void WriteText(const std::string& path, const std::string& text);
std::string ReadText(const std::string& path);

}  // namespace ocpb::testing
