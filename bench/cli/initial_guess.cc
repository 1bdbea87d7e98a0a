#include "bench/cli/initial_guess.h"

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench/cli/json_input.h"

namespace ocpb {
namespace {

using nlohmann::json;

[[noreturn]] void Fail(const std::string& path, const std::string& why) {
  throw std::invalid_argument("--initial-guess " + path + ": " + why);
}

// A JSON array of finite numbers (null stands for NaN in our records: not a usable control);
// errors name the file, the line and the field (bench/cli/json_input.h).
std::vector<double> Numbers(const JsonInputFile& in, const json& a, const std::string& what) {
  if (!a.is_array()) in.Fail(a, what, "must be an array of numbers");
  std::vector<double> v;
  v.reserve(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    if (!a[i].is_number() || !std::isfinite(a[i].get<double>())) {
      in.Fail(a[i], fmt::format("{}[{}]", what, i), "is not a finite number");
    }
    v.push_back(a[i].get<double>());
  }
  return v;
}

// Strictly increasing grid points, at least 2.
std::vector<double> Times(const JsonInputFile& in, const json& a, const std::string& what) {
  const std::vector<double> t = Numbers(in, a, what);
  if (t.size() < 2) in.Fail(a, what, "needs at least 2 points");
  for (size_t k = 1; k < t.size(); ++k) {
    if (!(t[k] > t[k - 1])) in.Fail(a, what, "is not strictly increasing");
  }
  return t;
}

// Rows of `points` finite numbers each (states or costates at a grid's points).
Mat Rows(const JsonInputFile& in, const json& rows, size_t points, const std::string& what) {
  if (!rows.is_array() || rows.empty()) in.Fail(rows, what, "must be a non-empty array of rows");
  Mat m(static_cast<int>(rows.size()), static_cast<int>(points));
  for (size_t i = 0; i < rows.size(); ++i) {
    const std::string row_name = fmt::format("{}[{}]", what, i);
    const std::vector<double> row = Numbers(in, rows[i], row_name);
    if (row.size() != points) {
      in.Fail(rows[i], row_name, fmt::format("has {} values, expected {}", row.size(), points));
    }
    for (size_t k = 0; k < points; ++k) m(static_cast<int>(i), static_cast<int>(k)) = row[k];
  }
  return m;
}

}  // namespace

InitialGuess ReadInitialGuess(const std::string& path) {
  // Size and nesting limits; every error "--initial-guess FILE:LINE: FIELD: rule".
  const JsonInputFile in(path, kMaxRecordBytes, "record", "--initial-guess " + OneLine(path));
  const json& record = in.document();
  if (!record.is_object() || !record.contains("trajectory") || !record["trajectory"].is_object()) {
    Fail(path,
         "no \"trajectory\" object (expected an `ocpbench solve --json` record written without "
         "--no-trajectory)");
  }
  const json& traj = record["trajectory"];
  if (!traj.contains("t") || !traj.contains("u")) Fail(path, "trajectory needs \"t\" and \"u\"");
  const std::vector<double> t = Times(in, traj["t"], "trajectory.t");
  const json& u = traj["u"];
  if (!u.is_array() || u.empty()) Fail(path, "trajectory.u must be a non-empty array of rows");
  const int N = static_cast<int>(t.size()) - 1;
  Mat values(static_cast<int>(u.size()), N + 1);
  for (size_t i = 0; i < u.size(); ++i) {
    const std::vector<double> row = Numbers(in, u[i], fmt::format("trajectory.u[{}]", i));
    if (static_cast<int>(row.size()) != N) {
      Fail(path,
           fmt::format(
               "trajectory.u[{}] has {} values, expected one per interval ({})", i, row.size(), N));
    }
    for (int k = 0; k < N; ++k) values(static_cast<int>(i), k) = row[k];
    values(static_cast<int>(i), N) = row[N - 1];
  }
  const TimeGrid grid = TimeGrid::FromPoints(t);
  InitialGuess guess;
  // The record keeps one sample per interval: exact for piecewise-constant controls; for the
  // others (collocation polynomials) the linear interpolant of the samples is the closer guess.
  if (traj.contains("u_rule") && !traj["u_rule"].is_string()) {
    in.Fail(traj["u_rule"], "trajectory.u_rule", "must be a string");
  }
  const std::string rule = traj.value("u_rule", std::string());
  guess.controls = rule.find("constant") != std::string::npos
                       ? ControlTrajectory::PiecewiseConstant(grid, values.leftCols(N))
                       : ControlTrajectory::PiecewiseLinear(grid, values);
  if (traj.contains("own")) {
    const json& own = traj["own"];
    if (!own.is_object()) Fail(path, "trajectory.own must be an object");
    if (!own.contains("t") || !own.contains("x"))
      Fail(path, "trajectory.own needs \"t\" and \"x\"");
    const std::vector<double> ts = Times(in, own["t"], "trajectory.own.t");
    const TimeGrid own_grid = TimeGrid::FromPoints(ts);
    if (std::abs(own_grid.t0() - grid.t0()) > 1e-9 * (1.0 + std::abs(grid.tf())) ||
        std::abs(own_grid.tf() - grid.tf()) > 1e-9 * (1.0 + std::abs(grid.tf()))) {
      Fail(path,
           fmt::format("trajectory.own.t spans [{}, {}] but trajectory.t [{}, {}]",
                       own_grid.t0(),
                       own_grid.tf(),
                       grid.t0(),
                       grid.tf()));
    }
    guess.states = ControlTrajectory::PiecewiseLinear(
        own_grid, Rows(in, own["x"], ts.size(), "trajectory.own.x"));
    if (own.contains("p")) {
      guess.costates = ControlTrajectory::PiecewiseLinear(
          own_grid, Rows(in, own["p"], ts.size(), "trajectory.own.p"));
    }
  }
  return guess;
}

void CheckInitialGuess(const InitialGuess& guess, const Ocp& ocp, const std::string& path) {
  if (guess.controls.nu() != ocp.nu()) {
    Fail(path,
         fmt::format("the controls have dimension {} but problem '{}' has nu = {}",
                     guess.controls.nu(),
                     ocp.name(),
                     ocp.nu()));
  }
  for (const auto& [part, name] : {std::pair{&guess.states, "states (trajectory.own.x)"},
                                   std::pair{&guess.costates, "costates (trajectory.own.p)"}}) {
    if (*part && (*part)->nu() != ocp.nx()) {
      Fail(path,
           fmt::format("the {} have dimension {} but problem '{}' has nx = {}",
                       name,
                       (*part)->nu(),
                       ocp.name(),
                       ocp.nx()));
    }
  }
  const double t0 = guess.controls.grid().t0(), tf = guess.controls.grid().tf();
  const double tol = 1e-9 * (1.0 + std::abs(ocp.tf()));
  const bool end_ok =
      ocp.free_final_time() ? ocp.AdmitsFinalTime(tf) : std::abs(tf - ocp.tf()) <= tol;
  if (std::abs(t0 - ocp.t0()) > tol || !end_ok) {
    const auto& free = ocp.free_final_time();
    Fail(path,
         free ? fmt::format("the trajectory spans [{}, {}] but problem '{}' starts at {} and ends "
                            "within [{}, {}] (free final time)",
                            t0,
                            tf,
                            ocp.name(),
                            ocp.t0(),
                            free->lower,
                            free->upper)
              : fmt::format(
                    "the trajectory spans [{}, {}] but problem '{}' has the horizon [{}, {}]",
                    t0,
                    tf,
                    ocp.name(),
                    ocp.t0(),
                    ocp.tf()));
  }
}

}  // namespace ocpb
