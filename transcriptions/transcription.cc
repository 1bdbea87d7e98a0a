#include "transcriptions/transcription.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/invalid.h"
#include "transcriptions/radau_nodes.h"

namespace ocpb {
namespace {

std::string Interval(double a, double b) {
  std::ostringstream os;
  os << "[" << a << ", " << b << "]";
  return os.str();
}

// A guess covers [grid.t0(), end]: the grid's tf, or a free final time's start.
bool GuessCovers(const std::optional<ControlTrajectory>& guess,
                 const char* what,
                 const TimeGrid& grid,
                 double end,
                 std::string* error) {
  if (!guess) return true;
  const TimeGrid& g = guess->grid();
  const double tol = 1e-12 * std::max({1.0, std::abs(grid.t0()), std::abs(end)});
  if (g.size() < 2 || g.t0() > grid.t0() + tol || g.tf() < end - tol) {
    return Invalid(error,
                   std::string("transcription: the initial ") + what + " is defined on " +
                       (g.size() < 2 ? std::string("no interval") : Interval(g.t0(), g.tf())) +
                       ", which does not cover the grid " + Interval(grid.t0(), end));
  }
  return true;
}

}  // namespace

bool TranscriptionOptions::IsValidOnItsOwn(std::string* error) const {
  if (grid.size() < 2) return Invalid(error, "transcription: the grid has no interval");
  if (degree < 1 || degree > kMaxRadauPoints) {
    return Invalid(error,
                   "transcription: degree must be in [1, " + std::to_string(kMaxRadauPoints) +
                       "], got " + std::to_string(degree));
  }
  if (!degrees.empty()) {
    if (static_cast<int>(degrees.size()) != grid.intervals()) {
      return Invalid(error,
                     "transcription: degrees must have one entry per grid interval (" +
                         std::to_string(grid.intervals()) + "), got " +
                         std::to_string(degrees.size()));
    }
    for (int d : degrees) {
      if (d < 1 || d > kMaxRadauPoints) {
        return Invalid(error,
                       "transcription: every entry of degrees must be in [1, " +
                           std::to_string(kMaxRadauPoints) + "], got " + std::to_string(d));
      }
    }
  }
  if (initial_guess && initial_guess->nu() < 1) {
    return Invalid(error, "transcription: the initial guess has no control components");
  }
  if (initial_states && initial_states->nu() < 1) {
    return Invalid(error, "transcription: the initial states have no components");
  }
  std::string why;
  if (!scaling.IsValid(&why)) return Invalid(error, "transcription: " + why);
  if (!mesh.IsValid(&why)) return Invalid(error, "transcription: " + why);
  return true;
}

bool TranscriptionOptions::IsValid(std::string* error) const {
  return IsValidOnItsOwn(error) && GuessCovers(initial_guess, "guess", grid, grid.tf(), error) &&
         GuessCovers(initial_states, "states", grid, grid.tf(), error);
}

bool TranscriptionOptions::IsValidFor(const Ocp& ocp, std::string* error) const {
  if (!IsValidOnItsOwn(error)) return false;
  if (const std::string off = ocp.GridOffHorizon(grid, Ocp::HorizonEnd::kNominal); !off.empty()) {
    return Invalid(error, "transcription: " + off);
  }
  if (initial_guess && initial_guess->nu() != ocp.nu()) {
    return Invalid(error,
                   "transcription: the initial guess must have nu = " + std::to_string(ocp.nu()) +
                       " components, got " + std::to_string(initial_guess->nu()));
  }
  if (initial_states && initial_states->nu() != ocp.nx()) {
    return Invalid(error,
                   "transcription: the initial states must have nx = " + std::to_string(ocp.nx()) +
                       " components, got " + std::to_string(initial_states->nu()));
  }
  // Each guess covers the horizon the start is read on: [t0, tf], or [t0, T] at the guess's
  // own final time T for a free final time.
  const double end = GuessFinalTime(ocp);
  if (!GuessCovers(initial_guess, "guess", grid, end, error) ||
      !GuessCovers(initial_states, "states", grid, end, error)) {
    return false;
  }
  std::string why;
  if (!scaling.IsValidFor(ocp.nx(), ocp.nu(), &why)) return Invalid(error, "transcription: " + why);
  return true;
}

double TranscriptionOptions::GuessFinalTime(const Ocp& ocp) const {
  if (!ocp.free_final_time() || !initial_guess || initial_guess->grid().size() < 2) {
    return grid.tf();
  }
  const double T = initial_guess->grid().tf();
  return ocp.AdmitsFinalTime(T) ? T : grid.tf();
}

ControlTrajectory TranscribedNlp::StateTrajectory(ConstVecRef z) const {
  const Mat X = States(z);
  const TimeGrid g = StateGrid(z);
  if (X.size() == 0 || X.cols() != g.size()) return ControlTrajectory();
  return ControlTrajectory::PiecewiseLinear(g, X);
}

}  // namespace ocpb
