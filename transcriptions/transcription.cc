#include "transcriptions/transcription.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "transcriptions/radau_nodes.h"

namespace ocpb {
namespace {

bool Fail(std::string* error, const std::string& why) {
  if (error) *error = why;
  return false;
}

std::string Interval(double a, double b) {
  std::ostringstream os;
  os << "[" << a << ", " << b << "]";
  return os.str();
}

}  // namespace

bool TranscriptionOptions::IsValid(std::string* error) const {
  if (grid.size() < 2) return Fail(error, "transcription: the grid has no interval");
  if (degree < 1 || degree > kMaxRadauPoints) {
    return Fail(error,
                "transcription: degree must be in [1, " + std::to_string(kMaxRadauPoints) +
                    "], got " + std::to_string(degree));
  }
  if (initial_guess) {
    if (initial_guess->nu() < 1) {
      return Fail(error, "transcription: the initial guess has no control components");
    }
    const TimeGrid& g = initial_guess->grid();
    const double tol = 1e-12 * std::max({1.0, std::abs(grid.t0()), std::abs(grid.tf())});
    if (g.size() < 2 || g.t0() > grid.t0() + tol || g.tf() < grid.tf() - tol) {
      return Fail(error,
                  "transcription: the initial guess is defined on " +
                      (g.size() < 2 ? std::string("no interval") : Interval(g.t0(), g.tf())) +
                      ", which does not cover the grid " + Interval(grid.t0(), grid.tf()));
    }
  }
  std::string why;
  if (!scaling.IsValid(&why)) return Fail(error, "transcription: " + why);
  return true;
}

bool TranscriptionOptions::IsValidFor(const Ocp& ocp, std::string* error) const {
  if (!IsValid(error)) return false;
  const double tol = 1e-12 * std::max({1.0, std::abs(ocp.t0()), std::abs(ocp.tf())});
  if (std::abs(grid.t0() - ocp.t0()) > tol || std::abs(grid.tf() - ocp.tf()) > tol) {
    return Fail(error,
                "transcription: the grid " + Interval(grid.t0(), grid.tf()) +
                    " must span the horizon " + Interval(ocp.t0(), ocp.tf()));
  }
  if (initial_guess && initial_guess->nu() != ocp.nu()) {
    return Fail(error,
                "transcription: the initial guess must have nu = " + std::to_string(ocp.nu()) +
                    " components, got " + std::to_string(initial_guess->nu()));
  }
  std::string why;
  if (!scaling.IsValidFor(ocp.nx(), ocp.nu(), &why)) return Fail(error, "transcription: " + why);
  return true;
}

}  // namespace ocpb
