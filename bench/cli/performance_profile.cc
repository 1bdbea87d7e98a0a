#include "bench/cli/performance_profile.h"

#include <cmath>
#include <limits>

namespace ocpb {

std::map<std::string, std::vector<double>> PerformanceRatios(
    const std::vector<ProfileEntry>& entries) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // instance -> solver -> its best value there (infinity: not solved)
  std::map<std::string, std::map<std::string, double>> table;
  for (const ProfileEntry& e : entries) {
    const double v = std::isfinite(e.value) ? e.value : kInf;
    auto [it, inserted] = table[e.instance].emplace(e.solver, v);
    if (!inserted && v < it->second) it->second = v;
  }
  std::map<std::string, std::vector<double>> ratios;
  for (const auto& [instance, values] : table) {
    double best = kInf;
    for (const auto& [solver, v] : values) best = std::min(best, v);
    if (!std::isfinite(best) || best <= 0.0) continue;
    for (const auto& [solver, v] : values) ratios[solver].push_back(v / best);
  }
  return ratios;
}

double ProfileFraction(const std::vector<double>& ratios, double tau) {
  if (ratios.empty()) return 0.0;
  size_t within = 0;
  for (double r : ratios) within += std::isfinite(r) && r <= tau ? 1 : 0;
  return static_cast<double>(within) / ratios.size();
}

}  // namespace ocpb
