#include "transcriptions/simulation_mesh_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ocpb {
namespace {

// One classical RK4 step of x' = f(t, x, u(t)) from a to b; the control's left limit at b
// (an interval's end belongs to it), its right limit elsewhere.
void SimulationRk4Step(
    const Ocp& ocp, const ControlTrajectory& u_of, double a, double b, bool b_is_end, VecRef x) {
  const int nx = static_cast<int>(x.size());
  Vec u(u_of.nu()), k1(nx), k2(nx), k3(nx), k4(nx);
  const double h = b - a, m = a + 0.5 * h;
  u_of.Evaluate(a, ControlTrajectory::Side::kRight, u);
  ocp.Dynamics(a, x, u, k1);
  u_of.Evaluate(m, ControlTrajectory::Side::kRight, u);
  ocp.Dynamics(m, x + 0.5 * h * k1, u, k2);
  ocp.Dynamics(m, x + 0.5 * h * k2, u, k3);
  u_of.Evaluate(b, b_is_end ? ControlTrajectory::Side::kLeft : ControlTrajectory::Side::kRight, u);
  ocp.Dynamics(b, x + h * k3, u, k4);
  x += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

}  // namespace

Vec IntervalSimulationErrors(const Ocp& ocp,
                             const TimeGrid& mesh,
                             const TimeGrid& state_times,
                             const Mat& states,
                             const ControlTrajectory& controls) {
  const int nx = ocp.nx(), N = mesh.intervals();
  const Vec inv_weight = (1.0 + states.cwiseAbs().rowwise().maxCoeff().array()).inverse();
  // The state point of each mesh node (the times are the same doubles: the layouts put t_k).
  std::vector<int> node_point(mesh.size(), -1);
  for (int k = 0, j = 0; k < mesh.size(); ++k) {
    while (j < state_times.size() && state_times.t(j) < mesh.t(k)) ++j;
    const double tol = 1e-12 * std::max(1.0, std::abs(mesh.t(k)));
    if (j < state_times.size() && std::abs(state_times.t(j) - mesh.t(k)) <= tol) {
      node_point[k] = j;
    } else {
      throw std::invalid_argument("IntervalSimulationErrors: mesh node " + std::to_string(k) +
                                  " is not a state point");
    }
  }
  Vec eta(N);
  Vec x(nx);
  for (int k = 0; k < N; ++k) {
    const int begin = node_point[k], end = node_point[k + 1];
    // Simulates the interval with m substeps per segment; returns eta and the simulated states.
    auto simulate = [&](int m, Mat* sim) {
      x = states.col(begin);
      double worst = 0.0;
      for (int j = begin + 1; j <= end; ++j) {
        const double a = state_times.t(j - 1), b = state_times.t(j);
        for (int s = 0; s < m; ++s) {
          const double sa = a + (b - a) * s / m, sb = s + 1 == m ? b : a + (b - a) * (s + 1) / m;
          SimulationRk4Step(ocp, controls, sa, sb, j == end && s + 1 == m, x);
        }
        sim->col(j - begin - 1) = x;
        worst =
            std::max(worst, ((x - states.col(j)).cwiseAbs().cwiseProduct(inv_weight)).maxCoeff());
      }
      return sim->allFinite() ? worst : std::numeric_limits<double>::quiet_NaN();
    };
    Mat coarse(nx, end - begin), fine(nx, end - begin);
    double e = simulate(4, &coarse);
    for (int m = 8; m <= 4096; m *= 2) {
      e = simulate(m, &fine);
      if (!std::isfinite(e)) break;
      const double moved =
          ((fine - coarse).cwiseAbs().array().colwise() * inv_weight.array()).maxCoeff();
      if (moved <= 1e-2 * e + 1e-13) break;
      coarse = fine;
    }
    eta[k] = e;
  }
  return eta;
}

}  // namespace ocpb
