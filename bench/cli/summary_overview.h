// The overview of a suite that spans many problems (the library): one table, problems as rows
// and method families as columns, and a Dolan-More profile of the families over the problems.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "bench/cli/record.h"

namespace ocpb {

/// A method family: solver, transcription and algorithm (grids, terminal forms and options of
/// one family share its column). "ipopt + lgr", "nlopt + hermite-simpson (LD_SLSQP)", "riccati-ip";
/// a `scheme` option other than euler (the Hamiltonian family's) is part of the family:
/// "hamiltonian-al (rk4)".
std::string MethodFamily(const Record& r);

/// How one family did on one problem: its best case (see OverviewMarkdown). NaN: none.
struct OverviewCell {
  int cases = 0;
  std::string status;        ///< the best case's status ("" when no case)
  double error = NAN;        ///< its rel. error vs the problem's continuous reference
  double cpu_seconds = NAN;  ///< its CPU seconds
  bool solved = false;       ///< converged and within the accuracy target (see below)
  /// Whether `error` is against the problem's continuous reference (else against the best
  /// converged J fine of any family).
  bool continuous = false;
};

/// The accuracy a family must reach on a problem to count as solving it: rel. error <= 1e-6
/// against the continuous reference; on a problem without one, J fine within 1e-6 (relative)
/// of the best converged J fine of any family.
inline constexpr double kOverviewAccuracy = 1e-6;

/// cell[problem][family] for the records' problems (in order of first appearance) and
/// families (likewise). A family's best case on a problem: converged cases before others, then
/// the smallest error (or J fine), then the least CPU.
struct Overview {
  std::vector<std::string> problems, families;
  std::vector<std::vector<OverviewCell>> cell;
};
Overview BuildOverview(const std::vector<Record>& records);

/// The overview as Markdown: the table (each cell "error (CPU s)", the status where not
/// converged, "n/a" for not_applicable), then per family the problems it solved, where it was
/// fastest, and rho(tau), the fraction of problems solved within a factor tau of the fastest
/// family's CPU (Dolan and More 2002), at tau = 1, 2, 10, 100, then the families by tag
/// (TagTableMarkdown, with the registered problems' tags). Empty for records of fewer than
/// `min_problems` problems.
std::string OverviewMarkdown(const std::vector<Record>& records, size_t min_problems = 3);

/// The families by problem tag: one row per tag (in ProblemTags() order) that a problem with a
/// continuous reference carries, one column per family; each cell "solved / applies to" over
/// those problems (a family applies to a problem when it ran on it and did not answer
/// not_applicable; solved as in OverviewCell). `tags_of` gives a problem's tags (none for a
/// problem it does not know). Empty when no problem has a continuous reference and a tag.
std::string TagTableMarkdown(
    const Overview& overview,
    const std::function<std::vector<std::string>(const std::string& problem)>& tags_of);

}  // namespace ocpb
