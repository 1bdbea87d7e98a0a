// One-step integrators on a time grid, with their exact discrete adjoints.
#pragma once

#include <string>

namespace ocpb {

/// The one-step schemes of OCPBench.
///  - kEuler: x_{k+1} = x_k + h f(t_k, x_k, u_k); running cost h L(t_k, x_k, u_k) (the paper's).
///  - kRk4:   classical 4-stage Runge-Kutta; the running cost is integrated as an extra state
///            with the same stages, so state and cost share the scheme's 4th order.
enum class Integrator { kEuler, kRk4 };

const char* ToString(Integrator integrator);
/// Parses "euler" or "rk4"; throws std::invalid_argument naming the valid values.
Integrator ParseIntegrator(const std::string& name);

}  // namespace ocpb
