#include "bench/cli/initial_guess.h"

#include <cmath>
#include <stdexcept>
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

}  // namespace

ControlTrajectory ReadInitialGuess(const std::string& path) {
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
  const std::vector<double> t = Numbers(in, traj["t"], "trajectory.t");
  if (t.size() < 2) Fail(path, "trajectory.t needs at least 2 points");
  for (size_t k = 1; k < t.size(); ++k) {
    if (!(t[k] > t[k - 1])) Fail(path, "trajectory.t is not strictly increasing");
  }
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
  // The record keeps one sample per interval: exact for piecewise-constant controls; for the
  // others (collocation polynomials) the linear interpolant of the samples is the closer guess.
  if (traj.contains("u_rule") && !traj["u_rule"].is_string()) {
    in.Fail(traj["u_rule"], "trajectory.u_rule", "must be a string");
  }
  const std::string rule = traj.value("u_rule", std::string());
  if (rule.find("constant") != std::string::npos) {
    return ControlTrajectory::PiecewiseConstant(grid, values.leftCols(N));
  }
  return ControlTrajectory::PiecewiseLinear(grid, values);
}

void CheckInitialGuess(const ControlTrajectory& guess, const Ocp& ocp, const std::string& path) {
  if (guess.nu() != ocp.nu()) {
    Fail(path,
         fmt::format("the controls have dimension {} but problem '{}' has nu = {}",
                     guess.nu(),
                     ocp.name(),
                     ocp.nu()));
  }
  const double t0 = guess.grid().t0(), tf = guess.grid().tf();
  const double tol = 1e-9 * (1.0 + std::abs(ocp.tf()));
  if (std::abs(t0 - ocp.t0()) > tol || std::abs(tf - ocp.tf()) > tol) {
    Fail(path,
         fmt::format("the trajectory spans [{}, {}] but problem '{}' has the horizon [{}, {}]",
                     t0,
                     tf,
                     ocp.name(),
                     ocp.t0(),
                     ocp.tf()));
  }
}

}  // namespace ocpb
