#include "bench/cli/summary_overview.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "bench/cli/performance_profile.h"
#include "bench/cli/summary.h"
#include "problems/registry.h"

namespace ocpb {
namespace {

constexpr double kOverviewNaN = std::numeric_limits<double>::quiet_NaN();

size_t OverviewIndexOf(std::vector<std::string>* names, const std::string& name) {
  const auto it = std::find(names->begin(), names->end(), name);
  if (it != names->end()) return static_cast<size_t>(it - names->begin());
  names->push_back(name);
  return names->size() - 1;
}

// The error of a record against its problem's continuous reference, NaN without one.
double ContinuousError(const Record& r) {
  if (!r.reference || r.reference->scheme != "continuous") return kOverviewNaN;
  return ReferenceError(r, *r.reference);
}

// Orders two cases of one family on one problem: is `a` the better one?
bool OverviewBetter(const Record& a, double ea, const Record& b, double eb) {
  const bool ca = a.status == "converged", cb = b.status == "converged";
  if (ca != cb) return ca;
  const bool fa = std::isfinite(ea), fb = std::isfinite(eb);
  if (fa != fb) return fa;
  if (fa && ea != eb) return ea < eb;
  return a.cpu_seconds < b.cpu_seconds;
}

// A registered problem's tags; none for a name the registry does not know (records of a
// problem registered by another program).
std::vector<std::string> RegisteredTags(const std::string& problem) {
  for (const ProblemInfo& info : Problems()) {
    if (info.name == problem) return info.tags;
  }
  return {};
}

std::string OverviewNumber(double v) {
  if (std::isnan(v)) return "-";
  return fmt::format("{:.2g}", v);
}

}  // namespace

std::string MethodFamily(const Record& r) {
  std::string label = r.solver;
  if (!r.transcription.empty()) label += " + " + r.transcription;
  if (!r.algorithm.empty()) label += " (" + r.algorithm + ")";
  // The Hamiltonian family's discretization is an option, not a transcription: its rk2/rk4
  // cases are another family than its Euler ones (orders 2 and 4 against 1).
  const auto scheme = r.options.find("scheme");
  if (scheme != r.options.end() && scheme->second != "euler") label += " (" + scheme->second + ")";
  return label;
}

Overview BuildOverview(const std::vector<Record>& records) {
  Overview o;
  for (const Record& r : records) {
    if (r.kind == "online") continue;
    OverviewIndexOf(&o.problems, r.problem);
    OverviewIndexOf(&o.families, MethodFamily(r));
  }
  o.cell.assign(o.problems.size(), std::vector<OverviewCell>(o.families.size()));
  // Without a continuous reference a case's error is measured against the best converged J
  // fine of any family on the same problem, seed, parameters and terminal form (GroupKey:
  // different seeds, settings or forms are different problems).
  std::map<std::string, double> best_J;
  for (const Record& r : records) {
    if (r.kind == "online" || r.status != "converged" || !std::isfinite(r.J_fine)) continue;
    const std::string key = GroupKey(r);
    if (!best_J.count(key) || r.J_fine < best_J[key]) best_J[key] = r.J_fine;
  }
  const auto error_of = [&](const Record& r) {
    if (r.reference && r.reference->scheme == "continuous") return ContinuousError(r);
    const auto it = best_J.find(GroupKey(r));
    if (it == best_J.end() || !std::isfinite(r.J_fine)) return kOverviewNaN;
    return std::abs(r.J_fine - it->second) / std::max(1.0, std::abs(it->second));
  };
  std::vector<std::vector<const Record*>> best(
      o.problems.size(), std::vector<const Record*>(o.families.size(), nullptr));
  for (const Record& r : records) {
    if (r.kind == "online") continue;
    const size_t p = OverviewIndexOf(&o.problems, r.problem);
    const size_t f = OverviewIndexOf(&o.families, MethodFamily(r));
    OverviewCell& c = o.cell[p][f];
    ++c.cases;
    const Record*& b = best[p][f];
    if (!b || OverviewBetter(r, error_of(r), *b, error_of(*b))) b = &r;
  }
  for (size_t p = 0; p < o.problems.size(); ++p) {
    for (size_t f = 0; f < o.families.size(); ++f) {
      const Record* b = best[p][f];
      if (!b) continue;
      OverviewCell& c = o.cell[p][f];
      c.status = b->status;
      c.error = error_of(*b);
      c.cpu_seconds = b->cpu_seconds;
      c.solved = b->status == "converged" && std::isfinite(c.error) && c.error <= kOverviewAccuracy;
      c.continuous = b->reference && b->reference->scheme == "continuous";
    }
  }
  return o;
}

std::string OverviewMarkdown(const std::vector<Record>& records, size_t min_problems) {
  const Overview o = BuildOverview(records);
  if (o.problems.size() < min_problems) return "";
  std::ostringstream md;
  md << "## Overview: problems x method families\n\n"
     << fmt::format(
            "Each cell is a family's best case on the problem, over its seeds and settings "
            "(converged first, then the smallest error, then the least CPU): its rel. error vs "
            "the problem's continuous reference (|Jbar fine - reference| / |reference|; for a "
            "problem without one, |J fine - best converged J fine of any family on the same "
            "seed, parameters and terminal form| / max(1, |best|)) and its CPU seconds; "
            "a status other than converged is named; n/a = not_applicable (the method does not "
            "take the problem; the record says why). A family *solves* a problem when that case "
            "converged within {:g}. The tables below break every cell down by N and terminal "
            "form.\n\n",
            kOverviewAccuracy);
  md << "| problem |";
  for (const std::string& f : o.families) md << " " << f << " |";
  md << "\n|---|";
  for (size_t f = 0; f < o.families.size(); ++f) md << "---|";
  md << "\n";
  for (size_t p = 0; p < o.problems.size(); ++p) {
    md << "| " << o.problems[p] << " |";
    for (const OverviewCell& c : o.cell[p]) {
      if (c.cases == 0) {
        md << " |";
      } else if (c.status == "not_applicable") {
        md << " n/a |";
      } else {
        md << " " << (c.solved ? "**" : "") << OverviewNumber(c.error) << (c.solved ? "**" : "")
           << fmt::format(" ({:.2g} s)", c.cpu_seconds)
           << (c.status == "converged" ? "" : " " + c.status) << " |";
      }
    }
    md << "\n";
  }
  // The profile: CPU seconds of the families that solved each problem.
  std::vector<ProfileEntry> entries;
  for (size_t p = 0; p < o.problems.size(); ++p) {
    for (size_t f = 0; f < o.families.size(); ++f) {
      const OverviewCell& c = o.cell[p][f];
      if (c.cases == 0 || c.status == "not_applicable") continue;
      entries.push_back(
          {o.problems[p],
           o.families[f],
           c.solved ? std::max(c.cpu_seconds, 1e-6) : std::numeric_limits<double>::infinity()});
    }
  }
  const auto ratios = PerformanceRatios(entries);
  md << "\nDolan-More profile over the problems (Dolan and More 2002): a family's instances "
        "are the problems it applies to; rho(tau) is the fraction of them it solved (as above) "
        "with CPU within a factor tau of the fastest family that solved the problem.\n\n"
     << "| family | applies to | solved | fastest | rho(1) | rho(2) | rho(10) | rho(100) |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (size_t f = 0; f < o.families.size(); ++f) {
    int applies = 0, solved = 0;
    for (size_t p = 0; p < o.problems.size(); ++p) {
      const OverviewCell& c = o.cell[p][f];
      if (c.cases == 0 || c.status == "not_applicable") continue;
      ++applies;
      solved += c.solved ? 1 : 0;
    }
    const auto it = ratios.find(o.families[f]);
    const std::vector<double> none;
    const std::vector<double>& r = it == ratios.end() ? none : it->second;
    // PerformanceRatios leaves out the problems no family solved; they count here as
    // applicable and unsolved, so rho is a fraction of the problems the family applies to.
    const auto rho = [&](double tau) {
      int within = 0;
      for (double x : r) within += x <= tau ? 1 : 0;
      return applies > 0 ? static_cast<double>(within) / applies : 0.0;
    };
    int fastest = 0;
    for (double x : r) fastest += x == 1.0 ? 1 : 0;
    md << fmt::format("| {} | {} | {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} |\n",
                      o.families[f],
                      applies,
                      solved,
                      fastest,
                      rho(1.0),
                      rho(2.0),
                      rho(10.0),
                      rho(100.0));
  }
  md << "\n" << TagTableMarkdown(o, RegisteredTags);
  return md.str();
}

std::string TagTableMarkdown(
    const Overview& o,
    const std::function<std::vector<std::string>(const std::string& problem)>& tags_of) {
  // Per problem with a continuous reference, its tags; per tag, how many such problems.
  std::vector<std::vector<std::string>> tags(o.problems.size());
  std::map<std::string, int> problems_of_tag;
  for (size_t p = 0; p < o.problems.size(); ++p) {
    bool continuous = false;
    for (const OverviewCell& c : o.cell[p]) continuous = continuous || c.continuous;
    if (!continuous) continue;
    tags[p] = tags_of(o.problems[p]);
    for (const std::string& t : tags[p]) ++problems_of_tag[t];
  }
  if (problems_of_tag.empty()) return "";
  std::ostringstream md;
  md << "Families by problem tag, over the problems with a continuous reference: each cell is "
        "solved / applies to (the problems of the tag the family ran on without answering "
        "not_applicable; solved as above). Tags overlap.\n\n| tag (problems) |";
  for (const std::string& f : o.families) md << " " << f << " |";
  md << "\n|---|";
  for (size_t f = 0; f < o.families.size(); ++f) md << "---|";
  md << "\n";
  for (const ProblemTag& tag : ProblemTags()) {
    const auto count = problems_of_tag.find(tag.name);
    if (count == problems_of_tag.end()) continue;
    md << "| " << tag.name << " (" << count->second << ") |";
    for (size_t f = 0; f < o.families.size(); ++f) {
      int applies = 0, solved = 0;
      for (size_t p = 0; p < o.problems.size(); ++p) {
        const OverviewCell& c = o.cell[p][f];
        const bool tagged = std::find(tags[p].begin(), tags[p].end(), tag.name) != tags[p].end();
        if (!tagged || c.cases == 0 || c.status == "not_applicable") continue;
        ++applies;
        solved += c.solved ? 1 : 0;
      }
      md << (applies == 0 ? std::string(" - |") : fmt::format(" {} / {} |", solved, applies));
    }
    md << "\n";
  }
  md << "\n";
  return md.str();
}

}  // namespace ocpb
