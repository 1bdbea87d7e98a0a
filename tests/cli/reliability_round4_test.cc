// Issue 41's leftovers, each as a class tried with many values: Ipopt's options are accepted by
// the check exactly when the linked Ipopt accepts them (the check asks Ipopt, no list of its
// rules), no output of any command names a run folder's files, `online` checks its horizon as
// `solve` does, and a thread the system refuses does not end the channel prediction.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/cli/output_place.h"
#include "solvers/ipopt_adapter.h"
#include "tests/cli/run_ocpbench.h"

namespace ocpb {
// Named, not anonymous: the unity build puts this file beside the other reliability tests.
namespace round4 {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::ProgramRun;
using testing::RunOcpbenchProgram;

// min (z0 - 1)^2 + (z1 - 2)^2 s.t. z0 + z1 = 1, z0^2 + z1 <= 3, -1 <= z0 <= 2: an equality and
// an inequality row, a bounded and a free variable, an exact Hessian.
class SmallNlp final : public Nlp {
 public:
  SmallNlp() {
    jac_rows_ = {0, 0, 1, 1};
    jac_cols_ = {0, 1, 0, 1};
    hess_rows_ = {0, 1};
    hess_cols_ = {0, 1};
  }
  int num_variables() const override { return 2; }
  int num_constraints() const override { return 2; }
  void Bounds(Vec* zl, Vec* zu, Vec* gl, Vec* gu) const override {
    const double inf = std::numeric_limits<double>::infinity();
    *zl = Vec(2);
    *zu = Vec(2);
    *gl = Vec(2);
    *gu = Vec(2);
    *zl << -1.0, -inf;
    *zu << 2.0, inf;
    *gl << 1.0, -inf;
    *gu << 1.0, 3.0;
  }
  Vec StartingPoint() const override { return Vec::Constant(2, 0.5); }
  bool Objective(ConstVecRef z, double* f) const override {
    *f = (z[0] - 1.0) * (z[0] - 1.0) + (z[1] - 2.0) * (z[1] - 2.0);
    return true;
  }
  bool Gradient(ConstVecRef z, VecRef g) const override {
    g[0] = 2.0 * (z[0] - 1.0);
    g[1] = 2.0 * (z[1] - 2.0);
    return true;
  }
  bool Constraints(ConstVecRef z, VecRef g) const override {
    g[0] = z[0] + z[1];
    g[1] = z[0] * z[0] + z[1];
    return true;
  }
  bool JacobianValues(ConstVecRef z, VecRef v) const override {
    v[0] = v[1] = v[3] = 1.0;
    v[2] = 2.0 * z[0];
    return true;
  }
  bool HasHessian() const override { return true; }
  bool HessianValues(ConstVecRef, double sigma, ConstVecRef lambda, VecRef v) const override {
    v[0] = 2.0 * sigma + 2.0 * lambda[1];
    v[1] = 2.0 * sigma;
    return true;
  }
};

std::string NumberText(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// Values of one option worth trying: just beyond each registered bound and one value within
// them (an ordinary one, else the default); strings: every listed value and a misspelling.
std::vector<std::string> ValuesToTry(const IpoptOptionSpec& spec) {
  std::vector<std::string> out;
  if (spec.type == IpoptOptionType::kString) {
    out = spec.values;
    out.push_back("no-such-value");
    return out;
  }
  const bool integer = spec.type == IpoptOptionType::kInteger;
  std::vector<double> v;
  const double lo = spec.bounds.min, hi = spec.bounds.max;
  if (std::isfinite(lo)) {
    v.push_back(integer ? lo - 1.0 : (lo == 0.0 ? -1e-3 : lo - std::abs(lo) * 1e-3));
  }
  if (std::isfinite(hi)) {
    v.push_back(integer ? hi + 1.0 : hi + std::max(1e-3, std::abs(hi) * 1e-3));
  }
  // One value within the bounds: an ordinary one, else the default.
  bool within = false;
  for (double x : {3.0, 0.5, 1.0}) {
    if (x != spec.default_value && spec.bounds.Contains(x)) {
      v.push_back(x);
      within = true;
      break;
    }
  }
  if (std::isfinite(spec.default_value) && !within) v.push_back(spec.default_value);
  for (double x : v) {
    if (integer && std::abs(x) > 2e9) continue;
    out.push_back(integer ? std::to_string(static_cast<long long>(std::lround(x))) : NumberText(x));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// What the linked Ipopt itself makes of the settings: OCPBench's own check left out
// (SolveNlpWithIpoptUnchecked), on a real NLP, in the starts a solve may make (an exact and a
// limited-memory Hessian, cold and warm; `all_starts` false: the exact cold and the
// limited-memory warm one, which take each side of both). "" when every start runs, else the
// start refused and why.
std::string IpoptItself(const std::vector<std::pair<const IpoptOptionSpec*, std::string>>& set,
                        bool all_starts = true) {
  const SmallNlp nlp;
  IpoptOptions options;
  options.max_iter = 5;  // a run is enough: what matters is whether Ipopt starts at all
  for (const auto& [spec, value] : set) {
    IpoptOptionValue v;
    v.name = spec->name;
    v.type = spec->type;
    if (spec->type == IpoptOptionType::kNumber) v.number = std::stod(value);
    if (spec->type == IpoptOptionType::kInteger) v.integer = std::stoi(value);
    if (spec->type == IpoptOptionType::kString) v.text = value;
    options.extra.push_back(v);
  }
  NlpMultipliers warm{Vec::Zero(2), Vec::Ones(2), Vec::Ones(2)};
  for (const char* hessian : {"exact", "limited-memory"}) {
    options.hessian_approximation = hessian;
    for (const bool with_multipliers : {false, true}) {
      if (!all_starts && with_multipliers == (std::string(hessian) == "exact")) continue;
      const NlpSolution s = SolveNlpWithIpoptUnchecked(
          nlp, nlp.StartingPoint(), options, with_multipliers ? warm : NlpMultipliers());
      if (s.solver_status == "Invalid_Option") {
        return std::string(hessian) + (with_multipliers ? ", warm" : ", cold") + ": " + s.message;
      }
    }
  }
  return "";
}

// OCPBench's check of the same settings: "" when accepted, else its message.
std::string OcpbenchCheck(const std::vector<std::pair<const IpoptOptionSpec*, std::string>>& set) {
  std::map<std::string, std::string> text = {{"max_iter", "5"}};
  for (const auto& [spec, value] : set) text[spec->name] = value;
  try {
    IpoptOptions::Apply(OptionMap(text), IpoptOptions());
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// Every Ipopt option OCPBench accepts is accepted by the linked Ipopt with the same value, and
// every value the check refuses Ipopt refuses too (in some start a solve may make); the same for
// the rules that tie two options, and for OCPBench's own fields together (which the check does
// not put to Ipopt when no pass-through option is set). Values within an option's bounds are
// tried in batches of unrelated options (a batch both sides refuse is tried value by value):
// each start of Ipopt costs tens of ms under the sanitizers.
TEST(IpoptOptionsRoundTrip, TheCheckAcceptsExactlyWhatIpoptAccepts) {
  using Set = std::vector<std::pair<const IpoptOptionSpec*, std::string>>;
  int tried = 0, refused = 0;
  std::string mismatches;
  // Whether both sides refuse.
  auto compare = [&](const Set& set, bool all_starts) {
    const std::string ours = OcpbenchCheck(set);
    const std::string theirs = IpoptItself(set, all_starts);
    std::string what;
    for (const auto& [spec, value] : set) what += spec->name + "=" + value + " ";
    if (ours.empty() != theirs.empty()) {
      mismatches += what + "| ocpbench: " + (ours.empty() ? "accepted" : ours) +
                    " | ipopt: " + (theirs.empty() ? "accepted" : theirs) + "\n";
    }
    // A refusal is one line naming an option of the set.
    if (!ours.empty()) {
      ++refused;
      EXPECT_EQ(ours.find('\n'), std::string::npos) << ours;
      bool named = false;
      for (const auto& [spec, value] : set) {
        named = named || ours.find(spec->name) != std::string::npos;
      }
      EXPECT_TRUE(named) << what << ": " << ours;
    }
    tried += static_cast<int>(set.size());
    return !ours.empty() && !theirs.empty();
  };
  // Ipopt writes what it refuses to the console (before its print_level applies): kept out of
  // the test's log.
  ::testing::internal::CaptureStdout();
  std::vector<std::pair<const IpoptOptionSpec*, std::string>> within;
  for (const IpoptOptionSpec& spec : IpoptOptionTable()) {
    // OCPBench's own meanings: the Hessian is chosen by the NLP (auto), the output file's place
    // is checked as every output's is (below), print_level's values only change the console.
    // Ipopt 3.11's derivative checker leaks (LeakSanitizer), and checks no option rule.
    if (spec.name == "hessian_approximation" || spec.name == "output_file" ||
        spec.name == "print_level" || spec.name == "derivative_test") {
      continue;
    }
    for (const std::string& value : ValuesToTry(spec)) {
      const bool in =
          spec.type == IpoptOptionType::kString
              ? std::find(spec.values.begin(), spec.values.end(), value) != spec.values.end()
              : spec.bounds.Contains(std::stod(value));
      if (in) {
        within.emplace_back(&spec, value);
      } else {
        compare({{&spec, value}}, false);  // out of range: refused before any start
      }
    }
  }
  // Batches of up to 12 values of distinct options.
  while (!within.empty()) {
    Set batch, rest;
    for (const auto& entry : within) {
      const bool taken = std::any_of(
          batch.begin(), batch.end(), [&](const auto& b) { return b.first == entry.first; });
      (taken || batch.size() >= 12 ? rest : batch).push_back(entry);
    }
    if (compare(batch, true)) {
      for (const auto& entry : batch) compare({entry}, true);
    }
    within = rest;
  }
  // The rules that tie two options, which no single value shows.
  for (const IpoptOrderedPair& pair : IpoptOrderedPairs()) {
    const IpoptOptionSpec* low = FindIpoptOption(pair.low);
    const IpoptOptionSpec* high = FindIpoptOption(pair.high);
    ASSERT_TRUE(low != nullptr && high != nullptr) << pair.low;
    const bool integer = low->type == IpoptOptionType::kInteger;
    for (const auto& [a, b] : std::vector<std::pair<double, double>>{{1, 2}, {2, 1}, {3, 3}}) {
      auto text = [&](double x) {
        return integer ? std::to_string(static_cast<int>(x)) : NumberText(x * 1e-3);
      };
      compare({{low, text(a)}, {high, text(b)}}, true);
    }
  }
  const IpoptOptionSpec* mehrotra = FindIpoptOption("mehrotra_algorithm");
  const IpoptOptionSpec* mu_strategy = FindIpoptOption("mu_strategy");
  ASSERT_TRUE(mehrotra != nullptr && mu_strategy != nullptr);
  compare({{mehrotra, "yes"}, {mu_strategy, "monotone"}}, true);
  compare({{mehrotra, "yes"}, {mu_strategy, "adaptive"}}, true);
  for (const auto& [name, value] :
       std::vector<std::pair<std::string, std::string>>{{"corrector_type", "affine"},
                                                        {"corrector_type", "none"},
                                                        {"adaptive_mu_globalization", "kkt-error"},
                                                        {"accept_every_trial_step", "yes"}}) {
    const IpoptOptionSpec* other = FindIpoptOption(name);
    ASSERT_NE(other, nullptr) << name;
    compare({{mehrotra, "yes"}, {mu_strategy, "adaptive"}, {other, value}}, true);
  }
  // OCPBench's own fields together (no pass-through option: the check does not start Ipopt).
  const IpoptOptionSpec* scaling = FindIpoptOption("nlp_scaling_method");
  const IpoptOptionSpec* tol = FindIpoptOption("tol");
  const IpoptOptionSpec* acceptable_tol = FindIpoptOption("acceptable_tol");
  const IpoptOptionSpec* objective = FindIpoptOption("obj_scaling_factor");
  ASSERT_TRUE(scaling && tol && acceptable_tol && objective);
  for (const char* strategy : {"monotone", "adaptive"}) {
    for (const char* method : {"none", "gradient-based"}) {
      for (const char* factor : {"1", "-2"}) {
        compare({{mu_strategy, strategy},
                 {scaling, method},
                 {objective, factor},
                 {tol, "1e-3"},
                 {acceptable_tol, "1e-9"}},
                true);
      }
    }
  }
  ::testing::internal::GetCapturedStdout();
  EXPECT_EQ(mismatches, "");
  EXPECT_GE(tried, 280);
  EXPECT_GE(refused, 100);
}

// Ipopt's output file: a place Ipopt cannot open is refused by the check, one it can is
// accepted, and the solve writes there.
TEST(IpoptOptionsRoundTrip, OutputFilePlacesAgreeWithIpopt) {
  const std::string dir = testing::FreshDirectory("r4-ipopt-output-file");
  const IpoptOptionSpec* spec = FindIpoptOption("output_file");
  ASSERT_NE(spec, nullptr);
  fs::create_directories(dir + "/folder");
  const std::vector<std::pair<std::string, bool>> kPlaces = {
      {dir + "/ok.log", true},
      {dir + "/folder/ok.log", true},
      {dir + "/folder/../ok2.log", true},
      {dir + "/no-such-folder/x.log", false},
      {dir + "/folder", false},
      {dir + "/" + std::string(300, 'x'), false},
      {dir + "/folder/" + std::string(300, 'y') + "/x.log", false},
  };
  for (const auto& [path, usable] : kPlaces) {
    const std::string ours = OcpbenchCheck({{spec, path}});
    EXPECT_EQ(ours.empty(), usable) << path << ": " << ours;
    if (!ours.empty()) {
      EXPECT_NE(ours.find("output_file"), std::string::npos) << ours;
      EXPECT_NE(IpoptItself({{spec, path}}), "") << path << ": Ipopt opens it";
    } else {
      EXPECT_EQ(IpoptItself({{spec, path}}), "") << path;
      EXPECT_TRUE(fs::exists(path)) << path;
    }
  }
}

// ---- no output names a run folder's files --------------------------------------------------

using testing::OneErrorLine;

std::string QuickSuite(int seeds) {
  std::string list;
  for (int i = 1; i <= seeds; ++i) list += (i > 1 ? "," : "") + std::to_string(i);
  return R"({"name": "r4", "groups": [{"problem": "double-integrator", "N": 10, "seeds": [)" +
         list + R"(], "methods": [{"solver": "hamiltonian", "options": {"max_iterations": 3}}]}]})";
}

// In `dir`: a whole run of a three-case suite in runs/ and the second of three shards of it in
// sweep/ (whose other shards' files are yet to be written).
void WriteTwoRunFolders(const std::string& dir) {
  testing::WriteText(dir + "/suite.json", QuickSuite(3));
  ASSERT_EQ(RunOcpbenchProgram({"run", "suite.json", "--out", "runs"}, dir).exit_code, 0);
  ASSERT_EQ(
      RunOcpbenchProgram({"run", "suite.json", "--out", "sweep", "--shard", "2/3"}, dir).exit_code,
      0);
}

// The shared checker (FilePlan) against run folders, by every spelling of their files: those
// that exist, those a shard has yet to write, through links to the file and to the folder.
TEST(OutputNeverNamesARunFolder, EverySpellingOfEveryRunFolderFile) {
  const std::string dir = testing::FreshDirectory("r4-run-folder-plan");
  ASSERT_NO_FATAL_FAILURE(WriteTwoRunFolders(dir));
  fs::create_directories(dir + "/other");
  fs::create_symlink("runs", dir + "/runs-link");
  fs::create_symlink("runs/records.jsonl", dir + "/records-link");
  fs::create_symlink("../sweep", dir + "/other/sweep-link");
  const std::string abs = fs::canonical(dir).string();
  std::vector<std::string> refused;
  for (const std::string& folder :
       std::vector<std::string>{"runs", "./runs", "other/../runs", abs + "/runs", "runs-link"}) {
    for (const std::string& name : std::vector<std::string>{"records.jsonl",
                                                            "records.jsonl.prev",
                                                            "records.jsonl.3.prev",
                                                            "summary.md",
                                                            "records.csv",
                                                            "derived.jsonl",
                                                            "suite.json",
                                                            ".ocpbench.lock"}) {
      refused.push_back(folder + "/" + name);
    }
  }
  for (const std::string& folder :
       std::vector<std::string>{"sweep", "./sweep/", "other/sweep-link", abs + "/sweep"}) {
    for (const std::string& name :
         std::vector<std::string>{"records.shard-1-of-3.jsonl",  // not written yet
                                  "records.shard-2-of-3.jsonl",
                                  "records.shard-3-of-3.jsonl.prev",
                                  "records.jsonl",
                                  "shards.json"}) {
      refused.push_back(folder + (folder.back() == '/' ? "" : "/") + name);
    }
  }
  refused.push_back("records-link");
  const std::vector<std::string> accepted = {"runs/ipopt.log",
                                             "runs/records.txt",
                                             "sweep/notes.md",
                                             "records.jsonl",  // no run folder here
                                             "other/records.jsonl",
                                             "other/summary.md"};
  const fs::path cwd = fs::current_path();
  fs::current_path(dir);
  for (const std::string& path : refused) {
    for (const char* what : {"--json", "--option output_file"}) {
      FilePlan plan;
      plan.Output(path, what);
      try {
        plan.Check();
        ADD_FAILURE() << path << " accepted";
      } catch (const std::invalid_argument& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(std::string(what) + " " + path + ": is ", 0), 0u) << message;
        EXPECT_NE(message.find("of the run folder"), std::string::npos) << message;
      }
    }
  }
  for (const std::string& path : accepted) {
    FilePlan plan;
    plan.Output(path, "--json");
    EXPECT_NO_THROW(plan.Check()) << path;
  }
  // A hard link to a run's records file elsewhere: a solver's output file, written in place,
  // is refused (it would empty the records); OCPBench's own outputs replace the name by a
  // rename, which leaves the run's file as it was, so they may.
  fs::create_hard_link("runs/records.jsonl", "other-name.txt");
  {
    FilePlan plan;
    plan.Output("other-name.txt", "option output_file", FilePlan::kSolverLog);
    try {
      plan.Check();
      ADD_FAILURE() << "a hard link as a solver's output file was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("has 2 names (hard links)"), std::string::npos)
          << e.what();
    }
    FilePlan own;
    own.Output("other-name.txt", "--json");
    EXPECT_NO_THROW(own.Check());
  }
  // A run's own plan: a case's file may not name a file of its folder that is yet to come.
  for (const std::string& name :
       std::vector<std::string>{"records.shard-1-of-3.jsonl", "records.shard-3-of-3.jsonl.prev"}) {
    FilePlan plan;
    plan.Output("fresh/" + name, "option output_file of case 1", "solver log");
    EXPECT_THROW(PlanRunFolder("fresh", "fresh/records.shard-2-of-3.jsonl", 3, &plan),
                 std::invalid_argument)
        << name;
  }
  fs::current_path(cwd);
  EXPECT_GE(refused.size(), 60u);
}

// The same through the commands: solve's --json and Ipopt's output file, online's, compare's,
// a suite case's output file naming another shard's records yet to be written.
TEST(OutputNeverNamesARunFolder, CommandsRefuseBeforeAnyWork) {
  const std::string dir = testing::FreshDirectory("r4-run-folder-cli");
  ASSERT_NO_FATAL_FAILURE(WriteTwoRunFolders(dir));
  fs::create_symlink("runs", dir + "/runs-link");
  const std::vector<std::string>& solve = testing::QuickIpoptSolve();
  std::vector<std::vector<std::string>> commands;
  for (const std::string& target : std::vector<std::string>{"runs/records.jsonl",
                                                            "./runs/../runs/records.jsonl.prev",
                                                            "runs-link/summary.md",
                                                            "sweep/records.shard-1-of-3.jsonl"}) {
    std::vector<std::string> a = solve;
    a.insert(a.end(), {"--json", target});
    commands.push_back(a);
    std::vector<std::string> b = solve;
    b.insert(b.end(), {"--option", "output_file=" + target});
    commands.push_back(b);
  }
  commands.push_back({"online",
                      "--problem",
                      "comm-path2d",
                      "--solver",
                      "ipopt",
                      "--option",
                      "output_file=runs/records.jsonl"});
  commands.push_back({"compare",
                      "runs/records.jsonl",
                      "sweep/records.shard-2-of-3.jsonl",
                      "--json",
                      "runs-link/records.csv"});
  commands.push_back({"channel", "simulate", "--no-files", "--json", "sweep/shards.json"});
  // A case's output file naming the records of a shard yet to run.
  testing::WriteText(
      dir + "/logs.json",
      R"({"name": "r4", "groups": [{"problem": "double-integrator", "N": 10, "seeds": [1, 2, 3],)"
      R"( "methods": [{"solver": "ipopt", "transcription": "euler", "options": )"
      R"({"output_file": "sweep/records.shard-3-of-3.jsonl"}}]}]})");
  const auto before = testing::SnapshotFiles(dir);
  for (const auto& args : commands) {
    const ProgramRun run = RunOcpbenchProgram(args, dir);
    std::string line;
    for (const std::string& a : args) line += a + " ";
    EXPECT_EQ(run.exit_code, 2) << line << ": " << run.err;
    EXPECT_TRUE(OneErrorLine(run)) << line << ": " << run.err;
    EXPECT_NE(run.err.find("of the run folder"), std::string::npos) << line << ": " << run.err;
  }
  for (const bool check : {false, true}) {
    std::vector<std::string> args = {"run", "logs.json", "--out", "sweep", "--shard", "1/3"};
    if (check) args.push_back("--check");
    const ProgramRun run = RunOcpbenchProgram(args, dir);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_TRUE(OneErrorLine(run)) << run.err;
    EXPECT_NE(run.err.find("option output_file of case 1"), std::string::npos) << run.err;
  }
  EXPECT_EQ(testing::SnapshotFiles(dir), before);
  EXPECT_FALSE(fs::exists(dir + "/sweep/records.shard-3-of-3.jsonl"));
}

// ---- online: the horizon check every solving command makes -----------------------------------

TEST(OnlineHorizon, AHorizonItsGridCannotSpanIsRefusedNamingTf) {
  const std::string dir = testing::FreshDirectory("r4-online-horizon");
  int tried = 0;
  for (const char* tf : {"4.9e-324", "1e-310", "2.2e-308"}) {
    for (const char* solver : {"hamiltonian", "ipopt"}) {
      const ProgramRun run = RunOcpbenchProgram({"online",
                                                 "--problem",
                                                 "comm-path2d",
                                                 "--solver",
                                                 solver,
                                                 "--set",
                                                 std::string("tf=") + tf,
                                                 "--json",
                                                 "o.json"},
                                                dir);
      EXPECT_EQ(run.exit_code, 2) << tf << ": " << run.err;
      EXPECT_TRUE(OneErrorLine(run)) << run.err;
      EXPECT_NE(run.err.find("tf: the horizon"), std::string::npos) << tf << ": " << run.err;
      ++tried;
    }
  }
  EXPECT_FALSE(fs::exists(dir + "/o.json"));
  EXPECT_GE(tried, 6);
}

}  // namespace round4
}  // namespace ocpb
