// End-to-end `ocpbench solve` with the NLP solvers: the JSON record's contract fields, a refused
// NLopt case, and --initial-guess (a previous record's controls as the starting point).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/cli/initial_guess.h"
#include "bench/cli/record.h"
#include "problems/registry.h"
#include "tests/cli/run_ocpbench.h"

namespace ocpb {
namespace {

using nlohmann::json;
using testing::ProgramRun;
using testing::RunOcpbenchProgram;

// The paper's problem on a coarse grid (dt = 1 s) with the path-loss channel (building the
// predicted channel map would dominate each run): cheap, and nu = 3 (acceleration, rate).
const std::vector<std::string> kPaper = {
    "--problem", "comm-path2d", "--set", "channel=0", "--N", "40"};

std::vector<std::string> Args(std::vector<std::string> head, const std::vector<std::string>& tail) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

json Solve(const std::string& dir, const std::vector<std::string>& args, int expected_exit = 0) {
  const ProgramRun run = RunOcpbenchProgram(Args(Args({"solve"}, kPaper), args), dir);
  EXPECT_EQ(run.exit_code, expected_exit) << run.err << run.out;
  return json::parse(testing::ReadText(dir + "/out.json"));
}

void ExpectContractFields(const json& r) {
  for (const char* key : {"status",
                          "solver_status",
                          "message",
                          "J",
                          "Jbar",
                          "terminal_violation",
                          "iterations",
                          "cpu_seconds",
                          "final_state",
                          "history",
                          "trajectory"}) {
    EXPECT_TRUE(r.contains(key)) << key;
  }
  EXPECT_EQ(r["status"], "converged") << r["message"];
  EXPECT_TRUE(r["J"].is_number());
  EXPECT_TRUE(r["Jbar"].is_number());
  EXPECT_LE(r["Jbar"].get<double>(), r["J"].get<double>());
  EXPECT_TRUE(r["terminal_violation"].is_number());
  EXPECT_GT(r["iterations"].get<int>(), 0);
  EXPECT_GT(r["cpu_seconds"].get<double>(), 0.0);
  ASSERT_EQ(r["final_state"].size(), 5u);  // position (2), velocity (2), bits
  ASSERT_FALSE(r["history"].empty());
  for (const json& h : r["history"]) {
    for (const char* key : {"iteration", "J", "theta", "armijo_j", "cpu_seconds"}) {
      ASSERT_TRUE(h.contains(key)) << key << " in " << h.dump();
    }
    EXPECT_TRUE(h["theta"].is_null());  // an NLP solver has no theta
    EXPECT_EQ(h["armijo_j"], -1);       // nor an Armijo exponent
  }
}

TEST(SolveCli, IpoptJsonHasTheContractFields) {
  const std::string dir = testing::FreshDirectory("solve-ipopt-json");
  const json r =
      Solve(dir, {"--solver", "ipopt", "--transcription", "euler", "--json", "out.json"});
  ExpectContractFields(r);
  EXPECT_EQ(r["solver_status"], "Solve_Succeeded");
  EXPECT_EQ(r["iterations"].get<size_t>() + 1, r["history"].size());  // Ipopt logs iterate 0
  // The Euler evaluator on the method's grid sees the NLP's own discrete problem.
  EXPECT_NEAR(r["J"].get<double>(), r["objective"].get<double>(), 1e-9 * r["J"].get<double>());
}

// A grid-sequenced polish (N = 200: the polish on 100 intervals first) writes the coarser grid's
// history rows with their `intervals` and the request grid's without; the record is snapshotted
// and so checked against the schema (records_match_schema).
TEST(SolveCli, GridSequencedPolishRecordsItsGrids) {
  const std::string dir = testing::FreshDirectory("solve-polish-sequenced");
  const ProgramRun run = RunOcpbenchProgram({"solve",
                                             "--problem",
                                             "comm-path2d",
                                             "--set",
                                             "channel=0",
                                             "--N",
                                             "200",
                                             "--solver",
                                             "hamiltonian-polish",
                                             "--terminal",
                                             "hard",
                                             "--json",
                                             "out.json"},
                                            dir);
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  const json r = json::parse(testing::ReadText(dir + "/out.json"));
  EXPECT_EQ(r["status"], "converged") << r["message"];
  EXPECT_EQ(r["solver_stats"]["coarse_levels"], 1.0);
  EXPECT_EQ(r["solver_stats"]["coarse_intervals"], 100.0);
  int coarse_rows = 0, request_rows = 0;
  for (const json& h : r["history"]) {
    if (h.contains("intervals")) {
      EXPECT_EQ(h["intervals"], 100);
      EXPECT_EQ(request_rows, 0) << "a coarse row after the request grid's";
      ++coarse_rows;
    } else {
      ++request_rows;
    }
  }
  EXPECT_GT(coarse_rows, 0);
  EXPECT_GT(request_rows, 0);
  EXPECT_EQ(ocpb::Record::FromJson(r).history.front().intervals, 100);
}

// A free final time: the record's final_time is the solution's T, and J_fine judges the controls
// on [0, T] for the indirect method and for Ipopt (T an NLP variable); a method that keeps the
// horizon fixed (single shooting) writes a not_applicable record (exit 0).
TEST(SolveCli, FreeFinalTimeRecordsTheSolutionsFinalTime) {
  const std::string dir = testing::FreshDirectory("solve-free-time");
  const std::vector<std::string> problem = {
      "solve", "--problem", "double-integrator-free-time", "--terminal", "hard", "--N", "100"};
  ProgramRun run =
      RunOcpbenchProgram(Args(problem, {"--solver", "indirect-newton", "--json", "out.json"}), dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  json r = json::parse(testing::ReadText(dir + "/out.json"));
  EXPECT_EQ(r["status"], "converged");
  const double T = r["final_time"].get<double>();
  EXPECT_NEAR(T, std::pow(18.0, 0.25), 2e-4);
  EXPECT_DOUBLE_EQ(r["solver_stats"]["final_time"].get<double>(), T);
  EXPECT_NEAR(r["Jbar_fine"].get<double>(), r["reference"]["value"].get<double>(), 3e-4);
  EXPECT_LE(r["terminal_violation_fine"].get<double>(), 2e-4);
  EXPECT_NE(run.out.find("final time = 2.0598"), std::string::npos) << run.out;

  // Ipopt with T as the NLP's variable reaches the same T (Hermite-Simpson: exact here).
  run = RunOcpbenchProgram(
      Args(problem,
           {"--solver", "ipopt", "--transcription", "hermite-simpson", "--json", "out.json"}),
      dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  r = json::parse(testing::ReadText(dir + "/out.json"));
  EXPECT_EQ(r["status"], "converged");
  EXPECT_NEAR(r["final_time"].get<double>(), std::pow(18.0, 0.25), 1e-8);
  EXPECT_NEAR(r["Jbar_fine"].get<double>(), r["reference"]["value"].get<double>(), 1e-8);

  run = RunOcpbenchProgram(
      Args(problem,
           {"--solver", "ipopt", "--transcription", "single-shooting", "--json", "out.json"}),
      dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  r = json::parse(testing::ReadText(dir + "/out.json"));
  EXPECT_EQ(r["status"], "not_applicable");
  EXPECT_TRUE(r["final_time"].is_null());
  EXPECT_NE(r["message"].get<std::string>().find("free final time"), std::string::npos);
}

// Every method with costates records where they come from, the costates on its own grid, and
// (lqr: a known p*, no terminal constraints) their error against p*; NLopt has no multipliers;
// a problem with terminal constraints in penalty form is not the problem p* belongs to: no error
// there.
TEST(SolveCli, RecordsCarryCostatesAndTheirErrorAgainstAKnownOptimum) {
  const std::string dir = testing::FreshDirectory("solve-costates");
  struct Expect {
    std::vector<std::string> method;
    std::string source;
    size_t points;     // the costate grid: N + 1, or N K + 1 for LGR
    double max_error;  // measured at N = 20: 1.2e-4, 2.7e-5, 0.445, 5.5e-3
  };
  for (const Expect& e : std::vector<Expect>{
           {{"--solver", "ipopt", "--transcription", "lgr"}, "NLP multipliers (lgr)", 61, 5e-4},
           {{"--solver", "ipopt", "--transcription", "hermite-simpson"},
            "NLP multipliers (hermite-simpson)",
            41,
            1e-4},
           {{"--solver", "hamiltonian"}, "discrete adjoint (euler)", 21, 0.6},
           {{"--solver", "indirect-newton"},
            "Newton's p (discretized maximum principle)",
            21,
            0.02}}) {
    const ProgramRun run = RunOcpbenchProgram(
        Args(Args({"solve", "--problem", "lqr", "--N", "20", "--json", "out.json"}, e.method), {}),
        dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const json r = json::parse(testing::ReadText(dir + "/out.json"));
    EXPECT_EQ(r["costate_source"], e.source);
    ASSERT_TRUE(r.contains("costates")) << e.source;
    EXPECT_EQ(r["costates"]["t"].size(), e.points) << e.source;
    ASSERT_EQ(r["costates"]["p"].size(), 2u) << e.source;
    EXPECT_EQ(r["costates"]["p"][1].size(), e.points) << e.source;
    ASSERT_TRUE(r.contains("costate_error")) << e.source;
    EXPECT_GT(r["costate_error"].get<double>(), 0.0) << e.source;
    EXPECT_LT(r["costate_error"].get<double>(), e.max_error) << e.source;
  }
  // NLopt gives no multipliers: with terminal constraints, single shooting has no costates (on
  // an unconstrained problem its costates are the plain discrete adjoint, recorded).
  const std::vector<std::string> nlopt = {"solve",
                                          "--problem",
                                          "double-integrator",
                                          "--terminal",
                                          "hard",
                                          "--solver",
                                          "nlopt",
                                          "--transcription",
                                          "single-shooting",
                                          "--N",
                                          "10",
                                          "--json",
                                          "out.json"};
  ProgramRun run = RunOcpbenchProgram(nlopt, dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  json r = json::parse(testing::ReadText(dir + "/out.json"));
  EXPECT_FALSE(r.contains("costate_source"));
  EXPECT_FALSE(r.contains("costates"));
  EXPECT_FALSE(r.contains("costate_error"));
  run = RunOcpbenchProgram({"solve",
                            "--problem",
                            "double-integrator",
                            "--solver",
                            "ipopt",
                            "--transcription",
                            "trapezoid",
                            "--N",
                            "10",
                            "--json",
                            "out.json"},
                           dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  r = json::parse(testing::ReadText(dir + "/out.json"));
  EXPECT_EQ(r["costate_source"], "NLP multipliers (trapezoid)");
  EXPECT_FALSE(r.contains("costate_error"));  // penalty form: p* is the hard form's
  run = RunOcpbenchProgram({"solve",
                            "--problem",
                            "double-integrator",
                            "--solver",
                            "ipopt",
                            "--transcription",
                            "trapezoid",
                            "--terminal",
                            "hard",
                            "--N",
                            "10",
                            "--set",
                            "tf=2",
                            "--json",
                            "out.json"},
                           dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  r = json::parse(testing::ReadText(dir + "/out.json"));
  EXPECT_FALSE(r.contains("costate_error"));  // p* is for the default parameters
}

TEST(SolveCli, NloptJsonHasTheContractFieldsAndRefusalsSayWhy) {
  const std::string dir = testing::FreshDirectory("solve-nlopt-json");
  const json r = Solve(dir,
                       {"--solver",
                        "nlopt",
                        "--transcription",
                        "single-shooting",
                        "--algorithm",
                        "AUGLAG",
                        "--json",
                        "out.json"});
  ExpectContractFields(r);
  EXPECT_EQ(r["iterations"].get<size_t>(), r["history"].size());  // one row per evaluation
  // L-BFGS takes bounds only; the ball |u| <= umax gives constraint rows: refused (exit 0: a
  // refusal is not a failure), nothing judged.
  const json refused = Solve(dir,
                             {"--solver",
                              "nlopt",
                              "--transcription",
                              "single-shooting",
                              "--algorithm",
                              "LD_LBFGS",
                              "--json",
                              "out.json"});
  EXPECT_EQ(refused["status"], "not_applicable");
  EXPECT_EQ(refused["solver_status"], "not_run");
  EXPECT_NE(refused["message"].get<std::string>().find("LD_LBFGS takes only bound constraints"),
            std::string::npos)
      << refused["message"];
  EXPECT_TRUE(refused["J"].is_null());
  EXPECT_TRUE(refused["history"].empty());
  // A size limit: SLSQP on n = 3 N = 120 variables with slsqp_max_variables = 100.
  const json too_big = Solve(dir,
                             {"--solver",
                              "nlopt",
                              "--transcription",
                              "single-shooting",
                              "--option",
                              "slsqp_max_variables=100",
                              "--json",
                              "out.json"});
  EXPECT_EQ(too_big["status"], "not_applicable");
  EXPECT_NE(too_big["message"].get<std::string>().find("n = 120 > slsqp_max_variables = 100"),
            std::string::npos)
      << too_big["message"];
}

// ---- --initial-guess ------------------------------------------------------------------------

TEST(SolveCli, IpoptStartsFromAHamiltonianRecordAndConverges) {
  const std::string dir = testing::FreshDirectory("solve-initial-guess");
  const json ham = Solve(dir, {"--solver", "hamiltonian", "--json", "out.json"});
  ASSERT_TRUE(ham["J"].is_number());
  testing::WriteText(dir + "/ham.json", testing::ReadText(dir + "/out.json"));
  // With max_iter = 0 Ipopt returns its starting point: the Hamiltonian controls exactly (the
  // states are simulated from them), so the evaluator finds the Hamiltonian record's J.
  const json start = Solve(dir,
                           {"--solver",
                            "ipopt",
                            "--transcription",
                            "euler",
                            "--initial-guess",
                            "ham.json",
                            "--option",
                            "max_iter=0",
                            "--json",
                            "out.json"});
  EXPECT_EQ(start["initial_guess"], "ham.json");
  EXPECT_NEAR(start["J"].get<double>(), ham["J"].get<double>(), 1e-9 * ham["J"].get<double>());
  // NLopt's first evaluation is at its starting point too.
  const json nlopt_start = Solve(dir,
                                 {"--solver",
                                  "nlopt",
                                  "--transcription",
                                  "single-shooting",
                                  "--initial-guess",
                                  "ham.json",
                                  "--option",
                                  "maxeval=1",
                                  "--json",
                                  "out.json"});
  EXPECT_EQ(nlopt_start["solver_status"], "MAXEVAL_REACHED");
  EXPECT_NEAR(nlopt_start["history"][0]["J"].get<double>(),
              ham["J"].get<double>(),
              1e-9 * ham["J"].get<double>());
  // And from there Ipopt converges, to the optimum it reaches from its default start.
  const json warm = Solve(dir,
                          {"--solver",
                           "ipopt",
                           "--transcription",
                           "euler",
                           "--initial-guess",
                           "ham.json",
                           "--json",
                           "out.json"});
  EXPECT_EQ(warm["status"], "converged") << warm["message"];
  const json cold =
      Solve(dir, {"--solver", "ipopt", "--transcription", "euler", "--json", "out.json"});
  EXPECT_NEAR(warm["J"].get<double>(), cold["J"].get<double>(), 1e-6 * cold["J"].get<double>());
  EXPECT_LT(warm["J"].get<double>(), ham["J"].get<double>());
}

TEST(SolveCli, BadInitialGuessFilesExitWithCodeTwo) {
  const std::string dir = testing::FreshDirectory("solve-bad-initial-guess");
  // A record of another problem: double-integrator has one control, comm-path2d three.
  ASSERT_EQ(RunOcpbenchProgram({"solve",
                                "--problem",
                                "double-integrator",
                                "--solver",
                                "hamiltonian",
                                "--N",
                                "10",
                                "--json",
                                "di.json"},
                               dir)
                .exit_code,
            0);
  ASSERT_EQ(RunOcpbenchProgram(Args(Args({"solve"}, kPaper),
                                    {"--solver",
                                     "hamiltonian",
                                     "--option",
                                     "max_iterations=1",
                                     "--no-trajectory",
                                     "--json",
                                     "bare.json"}),
                               dir)
                .exit_code,
            0);
  testing::WriteText(dir + "/broken.json", "{\"trajectory\": {\"t\": [0, 1");
  testing::WriteText(dir + "/short.json",
                     R"({"trajectory": {"t": [0, 20, 40], "u": [[0], [0], [0]]}})");
  testing::WriteText(dir + "/horizon.json",
                     R"({"trajectory": {"t": [0, 10, 20], "u": [[0, 0], [0, 0], [0, 0]]}})");
  const struct {
    const char* file;
    const char* expected;
  } cases[] = {
      {"missing.json", "--initial-guess missing.json: cannot read this record: No such file"},
      {"broken.json", "--initial-guess broken.json:1: not valid JSON at column 27"},
      {"bare.json", "--initial-guess bare.json: no \"trajectory\" object"},
      {"di.json", "the controls have dimension 1 but problem 'comm-path2d' has nu = 3"},
      {"short.json", "trajectory.u[0] has 1 values, expected one per interval (2)"},
      {"horizon.json",
       "the trajectory spans [0, 20] but problem 'comm-path2d' has the horizon [0, 40]"},
  };
  for (const auto& c : cases) {
    const ProgramRun run = RunOcpbenchProgram(
        Args(Args({"solve"}, kPaper),
             {"--solver", "ipopt", "--transcription", "euler", "--initial-guess", c.file}),
        dir);
    EXPECT_EQ(run.exit_code, 2) << c.file << ": " << run.err;
    EXPECT_EQ(run.err.rfind("ocpbench: error: ", 0), 0u) << run.err;
    EXPECT_NE(run.err.find(c.expected), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_TRUE(run.out.empty()) << "nothing may run: " << run.out;
  }
}

// Adaptive mesh refinement end to end: the record's mesh (stop reason, final nodes, one row per
// mesh with its solver status), the evaluator's grid is the final mesh (its re-simulation on the
// mesh's nodes), the report prints the history, the record reads back unchanged, and a bad
// mesh option is refused in one line naming it.
TEST(SolveCli, MeshRefinementIsRecordedAndJudgedOnTheFinalMesh) {
  const std::string dir = testing::FreshDirectory("solve-mesh-refinement");
  const std::vector<std::string> head = {"solve",
                                         "--problem",
                                         "double-integrator-bounded",
                                         "--solver",
                                         "ipopt",
                                         "--transcription",
                                         "hermite-simpson",
                                         "--terminal",
                                         "hard",
                                         "--N",
                                         "10"};
  const ProgramRun run = RunOcpbenchProgram(
      Args(head, {"--option", "mesh_tolerance=1e-7", "--json", "out.json"}), dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json r = json::parse(testing::ReadText(dir + "/out.json"));
  EXPECT_EQ(r["status"], "converged");
  ASSERT_TRUE(r.contains("mesh"));
  const json& mesh = r["mesh"];
  EXPECT_EQ(mesh["stop_reason"], "tolerance_met");
  ASSERT_GE(mesh["history"].size(), 2u);
  EXPECT_EQ(mesh["history"][0]["intervals"], 10);
  EXPECT_EQ(r["N"], 10);  // the request's grid; the final mesh is mesh.nodes
  const json& last = mesh["history"].back();
  EXPECT_EQ(last["intervals"].get<size_t>() + 1, mesh["nodes"].size());
  EXPECT_LE(last["max_error"].get<double>(), 1e-7);
  EXPECT_EQ(last["solver_status"], r["solver_status"]);
  for (const json& row : mesh["history"]) EXPECT_EQ(row["status"], "converged") << row.dump();
  // The evaluator's trajectory is on the final mesh.
  EXPECT_EQ(r["trajectory"]["t"], mesh["nodes"]);
  EXPECT_NEAR(r["Jbar_fine"].get<double>(), 6.0450277563, 1e-4 * 6.0450277563);
  EXPECT_NE(run.out.find("mesh refinement: tolerance_met"), std::string::npos) << run.out;
  EXPECT_EQ(Record::FromJson(r).ToJson(), r);

  const ProgramRun bad =
      RunOcpbenchProgram(Args(head, {"--option", "mesh_max_nodes=1", "--json", "bad.json"}), dir);
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("mesh_max_nodes"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find(">= 2"), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

// LGR's ph-refinement end to end: each history row carries the mesh's degrees (one per
// interval, summing to the collocation points the NLP size implies), the record reads back
// unchanged, and crossed degree limits are refused in one line.
TEST(SolveCli, PhRefinementRecordsTheDegrees) {
  const std::string dir = testing::FreshDirectory("solve-ph-refinement");
  const std::vector<std::string> head = {"solve",
                                         "--problem",
                                         "double-integrator-bounded",
                                         "--solver",
                                         "ipopt",
                                         "--transcription",
                                         "lgr",
                                         "--terminal",
                                         "hard",
                                         "--N",
                                         "4"};
  const ProgramRun run = RunOcpbenchProgram(
      Args(head, {"--option", "mesh_tolerance=1e-6", "--json", "out.json"}), dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json r = json::parse(testing::ReadText(dir + "/out.json"));
  ASSERT_TRUE(r.contains("mesh"));
  const json& mesh = r["mesh"];
  EXPECT_EQ(mesh["stop_reason"], "tolerance_met");
  ASSERT_GE(mesh["history"].size(), 2u);
  for (const json& row : mesh["history"]) {
    ASSERT_TRUE(row.contains("degrees")) << row.dump();
    EXPECT_EQ(row["degrees"].size(), row["intervals"].get<size_t>());
    int points = 0;
    for (const json& d : row["degrees"]) points += d.get<int>();
    EXPECT_EQ(row["nlp_variables"].get<int>(), points * 3 + 2);  // (nx + nu) per point + x(tf)
  }
  EXPECT_EQ(mesh["history"].back()["intervals"].get<size_t>() + 1, mesh["nodes"].size());
  EXPECT_NE(run.out.find("collocation points"), std::string::npos) << run.out;
  EXPECT_EQ(Record::FromJson(r).ToJson(), r);

  const ProgramRun bad = RunOcpbenchProgram(
      Args(head,
           {"--option", "mesh_min_degree=7", "--option", "mesh_max_degree=5", "--json", "b.json"}),
      dir);
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("mesh_max_degree"), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

// The reader itself: piecewise constant when the record says so (the record's controls
// exactly), piecewise linear through the samples otherwise.
TEST(InitialGuess, KeepsTheRecordsInterpolationRule) {
  const std::string dir = testing::FreshDirectory("initial-guess-reader");
  testing::WriteText(dir + "/pc.json",
                     R"({"trajectory": {"t": [0, 1, 2], "u": [[1, 3]],
                         "u_rule": "value at each interval's left end; piecewise constant"}})");
  testing::WriteText(dir + "/pl.json",
                     R"({"trajectory": {"t": [0, 1, 2], "u": [[1, 3]],
                         "u_rule": "value at each interval's left end; piecewise linear"}})");
  const ControlTrajectory pc = ReadInitialGuess(dir + "/pc.json").controls;
  const ControlTrajectory pl = ReadInitialGuess(dir + "/pl.json").controls;
  EXPECT_EQ(pc.nu(), 1);
  EXPECT_EQ(pc(0.5)[0], 1.0);
  EXPECT_EQ(pc(1.5)[0], 3.0);
  EXPECT_DOUBLE_EQ(pl(0.5)[0], 2.0);
  EXPECT_DOUBLE_EQ(pl(1.5)[0], 3.0);                         // the last sample held to tf
  const auto ocp = MakeProblem("double-integrator", {}, 0);  // horizon [0, 1]
  EXPECT_THROW(CheckInitialGuess({pc, {}, {}}, *ocp, "pc.json"), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
