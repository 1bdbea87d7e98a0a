// Dolan-More performance profiles (Dolan and More, "Benchmarking optimization software with
// performance profiles", Math. Program. 91, 2002): for each solver, the fraction of the instances
// it ran on where its measure is within a factor tau of the best solver's on that instance.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace ocpb {

/// One solver's measure on one instance (lower is better; NaN or infinity: not solved).
struct ProfileEntry {
  std::string instance, solver;
  double value = 0.0;
};

/// Each solver's performance ratios r = value / best over the instances it ran on (best: the
/// lowest finite value of any solver on the instance; r = infinity where the solver did not
/// solve it). Instances where no solver has a finite value > 0 are left out, as in
/// results/plot.py's profiles. Two entries of one solver on one instance count as its best.
std::map<std::string, std::vector<double>> PerformanceRatios(
    const std::vector<ProfileEntry>& entries);

/// rho(tau): the fraction of `ratios` that are finite and <= tau (0 for no ratios); at tau =
/// infinity, the fraction of the instances solved.
double ProfileFraction(const std::vector<double>& ratios, double tau);

}  // namespace ocpb
