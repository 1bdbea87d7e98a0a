// Build identity recorded with every result.
#pragma once

#include <string>

namespace ocpb {

/// The git commit OCPBench was built from ("-dirty" when the tree had changes; "unknown").
const char* GitCommit();
/// "ocpbench 0.1.0 (commit abc, g++ 12.2.0, Ipopt 3.11.9, NLopt 2.7.1)".
std::string VersionString();
/// Versions of the compiler and the solver libraries.
std::string CompilerVersion();
std::string IpoptVersion();
std::string NloptVersion();

}  // namespace ocpb
