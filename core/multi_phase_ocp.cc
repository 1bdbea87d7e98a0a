#include "core/multi_phase_ocp.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace ocpb {
namespace {

std::string PhaseName(const std::string& problem, int i) {
  return "multi-phase problem '" + problem + "': phase " + std::to_string(i + 1);
}

}  // namespace

std::vector<PhaseLink> MultiPhaseOcp::Continuity(int nx, const Vec& jump) {
  if (jump.size() != 0 && jump.size() != nx) {
    throw std::invalid_argument("MultiPhaseOcp::Continuity: jump has " +
                                std::to_string(jump.size()) + " entries, expected " +
                                std::to_string(nx) + " or none");
  }
  std::vector<PhaseLink> links;
  for (int k = 0; k < nx; ++k) links.push_back({k, k, jump.size() ? jump[k] : 0.0});
  return links;
}

MultiPhaseOcp::MultiPhaseOcp(std::string name,
                             std::vector<PhaseSpec> phases,
                             std::vector<std::vector<PhaseLink>> links)
    : name_(std::move(name)), phases_(std::move(phases)), links_(std::move(links)) {
  const int P = num_phases();
  if (P < 1) throw std::invalid_argument("multi-phase problem '" + name_ + "': no phase");
  if (static_cast<int>(links_.size()) != P - 1) {
    throw std::invalid_argument("multi-phase problem '" + name_ +
                                "': " + std::to_string(links_.size()) + " link lists for " +
                                std::to_string(P) + " phases (expected one per pair, " +
                                std::to_string(P - 1) + ")");
  }
  int nx = 0, nu = 0, nc = 0;
  for (int i = 0; i < P; ++i) {
    const PhaseSpec& s = phases_[i];
    const std::string where = PhaseName(name_, i);
    if (!s.ocp) throw std::invalid_argument(where + ": no problem");
    if (s.ocp->free_final_time()) {
      throw std::invalid_argument(where +
                                  ": has a free final time of its own (its duration "
                                  "is the multi-phase problem's decision)");
    }
    if (s.ocp->num_static_parameters() > 0) {
      throw std::invalid_argument(where +
                                  ": has static parameters of its own (not supported "
                                  "inside a phase)");
    }
    if (!(std::isfinite(s.min_duration) && std::isfinite(s.max_duration) && s.min_duration > 0.0 &&
          s.min_duration <= s.max_duration)) {
      std::ostringstream message;  // default stream format: 1e-07, not to_string's 0.000000
      message << where << ": duration bounds [" << s.min_duration << ", " << s.max_duration
              << "] must be finite with 0 < min <= max";
      throw std::invalid_argument(message.str());
    }
    state_offset_.push_back(nx);
    control_offset_.push_back(nu);
    path_offset_.push_back(nc);
    nx += s.ocp->nx();
    nu += s.ocp->nu();
    nc += s.ocp->num_path();
    if (s.ocp->HasInitialCost() && (i > 0 || s.ocp->HasFreeInitialState()))
      has_initial_cost_ = true;
  }
  for (int i = 0; i + 1 < P; ++i) {
    std::vector<bool> linked(phase(i + 1).nx(), false);
    for (const PhaseLink& l : links_[i]) {
      if (l.from_state < 0 || l.from_state >= phase(i).nx() || l.to_state < 0 ||
          l.to_state >= phase(i + 1).nx() || !std::isfinite(l.jump)) {
        throw std::invalid_argument(
            "multi-phase problem '" + name_ + "': link from phase " + std::to_string(i + 1) +
            " state " + std::to_string(l.from_state) + " to phase " + std::to_string(i + 2) +
            " state " + std::to_string(l.to_state) + ": index outside the phase's state (or " +
            "a jump that is not finite)");
      }
      // Two links into one state would be duplicate or contradictory equality rows.
      if (linked[l.to_state]) {
        throw std::invalid_argument("multi-phase problem '" + name_ + "': phase " +
                                    std::to_string(i + 2) + " state " + std::to_string(l.to_state) +
                                    " is linked twice");
      }
      linked[l.to_state] = true;
    }
  }
  duration_offset_ = nx;
  const int nx_total = nx + P;
  const Ocp& last = phase(P - 1);
  SetDimensions(nx_total, nu, last.num_terminal(), nc);
  SetHorizon(0.0, 1.0);

  // x(0): phase 1 as it declares, later phases free (their start is set by the links); the
  // durations follow as static parameters.
  Vec x0 = Vec::Zero(nx_total);
  Vec lo = Vec::Constant(nx_total, -std::numeric_limits<double>::infinity());
  Vec hi = Vec::Constant(nx_total, std::numeric_limits<double>::infinity());
  Vec state_lo = lo, state_hi = hi;
  bool any_state_bounds = false;
  ControlSet set;
  for (int i = 0; i < P; ++i) {
    const Ocp& p = phase(i);
    x0.segment(state_offset(i), p.nx()) = p.x0();
    if (i == 0) {
      const VectorBounds b = p.InitialNodeBounds();
      lo.segment(0, p.nx()) = b.lower;
      hi.segment(0, p.nx()) = b.upper;
    } else if (p.state_bounds()) {
      // A later phase's start is a decision (the links set it): its state bounds hold there
      // too (the initial node takes the initial-state bounds alone).
      lo.segment(state_offset(i), p.nx()) = p.state_bounds()->lower;
      hi.segment(state_offset(i), p.nx()) = p.state_bounds()->upper;
    }
    if (p.state_bounds()) {
      any_state_bounds = true;
      state_lo.segment(state_offset(i), p.nx()) = p.state_bounds()->lower;
      state_hi.segment(state_offset(i), p.nx()) = p.state_bounds()->upper;
    }
    for (const ControlSet::Block& b : p.control_set().blocks()) {
      if (b.kind == ControlSet::Kind::kBox) {
        set.AddBox(b.lower, b.upper);
      } else {
        set.AddBall(b.center, b.radius);
      }
    }
  }
  SetInitialState(x0);
  SetControlSet(set);
  if (any_state_bounds) SetStateBounds(state_lo, state_hi);
  // Boundary rows: links (equalities), events psi_i = 0 of the phases before the last, and
  // each phase's own boundary constraints with its bounds.
  std::vector<double> b_lo, b_hi;
  for (const auto& pair : links_) {
    for (size_t k = 0; k < pair.size(); ++k) {
      b_lo.push_back(0.0);
      b_hi.push_back(0.0);
    }
  }
  for (int i = 0; i < P; ++i) {
    event_row_.push_back(static_cast<int>(b_lo.size()));
    if (i + 1 < P) {
      for (int k = 0; k < phase(i).num_terminal(); ++k) {
        b_lo.push_back(0.0);
        b_hi.push_back(0.0);
      }
    }
  }
  for (int i = 0; i < P; ++i) {
    phase_boundary_row_.push_back(static_cast<int>(b_lo.size()));
    const VectorBounds& bb = phase(i).boundary_bounds();
    for (int k = 0; k < phase(i).num_boundary(); ++k) {
      b_lo.push_back(bb.lower[k]);
      b_hi.push_back(bb.upper[k]);
    }
  }
  if (!b_lo.empty()) {
    SetBoundaryConstraints(
        Eigen::Map<const Vec>(b_lo.data(), static_cast<Eigen::Index>(b_lo.size())),
        Eigen::Map<const Vec>(b_hi.data(), static_cast<Eigen::Index>(b_hi.size())));
  }
  // Initial-state bounds for x(0) (phase 1's, the others free), then the durations.
  if (P > 1 || phase(0).HasFreeInitialState()) SetInitialStateBounds(lo, hi);
  Vec d_lo(P), d_hi(P), d_guess(P);
  for (int i = 0; i < P; ++i) {
    d_lo[i] = phases_[i].min_duration;
    d_hi[i] = phases_[i].max_duration;
    const double nominal = phase(i).tf() - phase(i).t0();
    d_guess[i] = std::min(std::max(nominal, d_lo[i]), d_hi[i]);
  }
  SetStaticParameters(d_lo, d_hi, d_guess);
  if (last.terminal_weights_chosen() && last.num_terminal() > 0)
    SetTerminalWeights(last.terminal_weights());
}

double MultiPhaseOcp::PhaseTime(int i, double tau) const {
  return phase(i).t0() + tau * (phase(i).tf() - phase(i).t0());
}

bool MultiPhaseOcp::CountsInitialCost(int i) const {
  return phase(i).HasInitialCost() && (i > 0 || phase(0).HasFreeInitialState());
}

std::vector<MultiPhaseOcp::PhaseTrajectory> MultiPhaseOcp::SplitPhases(
    const std::vector<double>& tau, const Mat& X) const {
  if (X.rows() != nx() || X.cols() != static_cast<Eigen::Index>(tau.size())) {
    throw std::invalid_argument("MultiPhaseOcp::SplitPhases: states are " +
                                std::to_string(X.rows()) + " x " + std::to_string(X.cols()) +
                                ", expected " + std::to_string(nx()) + " x " +
                                std::to_string(tau.size()));
  }
  std::vector<PhaseTrajectory> out;
  double start = phase(0).t0();
  for (int i = 0; i < num_phases(); ++i) {
    PhaseTrajectory p;
    p.start_time = start;
    p.duration = X.cols() > 0 ? X(duration_index(i), 0) : 0.0;
    for (double s : tau) p.t.push_back(start + s * p.duration);
    p.x = X.block(state_offset(i), 0, phase(i).nx(), X.cols());
    start += p.duration;
    out.push_back(std::move(p));
  }
  return out;
}

// ---- values ----------------------------------------------------------------------------

void MultiPhaseOcp::Dynamics(double t, ConstVecRef x, ConstVecRef u, VecRef f) const {
  f.setZero();
  for (int i = 0; i < num_phases(); ++i) {
    const Ocp& p = phase(i);
    const double T = x[duration_index(i)];
    auto fi = f.segment(state_offset(i), p.nx());
    p.Dynamics(PhaseTime(i, t),
               x.segment(state_offset(i), p.nx()),
               u.segment(control_offset(i), p.nu()),
               fi);
    fi *= T;
  }
}

double MultiPhaseOcp::RunningCost(double t, ConstVecRef x, ConstVecRef u) const {
  double L = 0.0;
  for (int i = 0; i < num_phases(); ++i) {
    const Ocp& p = phase(i);
    L += x[duration_index(i)] * p.RunningCost(PhaseTime(i, t),
                                              x.segment(state_offset(i), p.nx()),
                                              u.segment(control_offset(i), p.nu()));
  }
  return L;
}

double MultiPhaseOcp::TerminalCost(ConstVecRef x) const {
  double phi = 0.0;
  for (int i = 0; i < num_phases(); ++i)
    phi += phase(i).TerminalCost(x.segment(state_offset(i), phase(i).nx()));
  return phi;
}

double MultiPhaseOcp::InitialCost(ConstVecRef x0) const {
  double phi0 = 0.0;
  for (int i = 0; i < num_phases(); ++i) {
    if (CountsInitialCost(i))
      phi0 += phase(i).InitialCost(x0.segment(state_offset(i), phase(i).nx()));
  }
  return phi0;
}

void MultiPhaseOcp::TerminalConstraints(ConstVecRef x, VecRef psi) const {
  const int last = num_phases() - 1;
  phase(last).TerminalConstraints(x.segment(state_offset(last), phase(last).nx()), psi);
}

void MultiPhaseOcp::BoundaryConstraints(ConstVecRef x0, ConstVecRef xf, VecRef b) const {
  int row = 0;
  for (int i = 0; i + 1 < num_phases(); ++i) {
    for (const PhaseLink& l : links_[i]) {
      b[row++] = x0[state_offset(i + 1) + l.to_state] - xf[state_offset(i) + l.from_state] - l.jump;
    }
  }
  for (int i = 0; i + 1 < num_phases(); ++i) {
    const Ocp& p = phase(i);
    p.TerminalConstraints(xf.segment(state_offset(i), p.nx()),
                          b.segment(event_row_[i], p.num_terminal()));
  }
  for (int i = 0; i < num_phases(); ++i) {
    const Ocp& p = phase(i);
    if (p.num_boundary() == 0) continue;
    p.BoundaryConstraints(x0.segment(state_offset(i), p.nx()),
                          xf.segment(state_offset(i), p.nx()),
                          b.segment(phase_boundary_row_[i], p.num_boundary()));
  }
}

void MultiPhaseOcp::PathConstraints(double t, ConstVecRef x, ConstVecRef u, VecRef c) const {
  for (int i = 0; i < num_phases(); ++i) {
    const Ocp& p = phase(i);
    if (p.num_path() == 0) continue;
    p.PathConstraints(PhaseTime(i, t),
                      x.segment(state_offset(i), p.nx()),
                      u.segment(control_offset(i), p.nu()),
                      c.segment(path_offset_[i], p.num_path()));
  }
}

Vec MultiPhaseOcp::NominalControl() const {
  Vec u(nu());
  for (int i = 0; i < num_phases(); ++i)
    u.segment(control_offset(i), phase(i).nu()) = phase(i).CheckedNominalControl();
  return u;
}

// ---- first derivatives -----------------------------------------------------------------

void MultiPhaseOcp::DynamicsJacobian(
    double t, ConstVecRef x, ConstVecRef u, VecRef f, MatRef fx, MatRef fu) const {
  f.setZero();
  fx.setZero();
  fu.setZero();
  for (int i = 0; i < num_phases(); ++i) {
    const Ocp& p = phase(i);
    const int xo = state_offset(i), uo = control_offset(i), n = p.nx(), m = p.nu();
    const double T = x[duration_index(i)];
    Vec fi(n);
    Mat fxi(n, n), fui(n, m);
    p.DynamicsJacobian(PhaseTime(i, t), x.segment(xo, n), u.segment(uo, m), fi, fxi, fui);
    f.segment(xo, n) = T * fi;
    fx.block(xo, xo, n, n) = T * fxi;
    fx.block(xo, duration_index(i), n, 1) = fi;  // d(T f_i)/dT = f_i
    fu.block(xo, uo, n, m) = T * fui;
  }
}

void MultiPhaseOcp::RunningCostGradient(
    double t, ConstVecRef x, ConstVecRef u, double* L, VecRef Lx, VecRef Lu) const {
  *L = 0.0;
  Lx.setZero();
  Lu.setZero();
  for (int i = 0; i < num_phases(); ++i) {
    const Ocp& p = phase(i);
    const int xo = state_offset(i), uo = control_offset(i), n = p.nx(), m = p.nu();
    const double T = x[duration_index(i)];
    double Li = 0.0;
    Vec Lxi(n), Lui(m);
    p.RunningCostGradient(PhaseTime(i, t), x.segment(xo, n), u.segment(uo, m), &Li, Lxi, Lui);
    *L += T * Li;
    Lx.segment(xo, n) = T * Lxi;
    Lx[duration_index(i)] = Li;
    Lu.segment(uo, m) = T * Lui;
  }
}

void MultiPhaseOcp::TerminalCostGradient(ConstVecRef x, double* phi, VecRef phix) const {
  *phi = 0.0;
  phix.setZero();
  for (int i = 0; i < num_phases(); ++i) {
    const Ocp& p = phase(i);
    double phi_i = 0.0;
    Vec g(p.nx());
    p.TerminalCostGradient(x.segment(state_offset(i), p.nx()), &phi_i, g);
    *phi += phi_i;
    phix.segment(state_offset(i), p.nx()) = g;
  }
}

void MultiPhaseOcp::InitialCostGradient(ConstVecRef x0, double* phi0, VecRef grad) const {
  *phi0 = 0.0;
  grad.setZero();
  for (int i = 0; i < num_phases(); ++i) {
    if (!CountsInitialCost(i)) continue;
    const Ocp& p = phase(i);
    double v = 0.0;
    Vec g(p.nx());
    p.InitialCostGradient(x0.segment(state_offset(i), p.nx()), &v, g);
    *phi0 += v;
    grad.segment(state_offset(i), p.nx()) = g;
  }
}

void MultiPhaseOcp::BoundaryConstraintsJacobian(
    ConstVecRef x0, ConstVecRef xf, VecRef b, MatRef b_x0, MatRef b_xf) const {
  b_x0.setZero();
  b_xf.setZero();
  BoundaryConstraints(x0, xf, b);
  int row = 0;
  for (int i = 0; i + 1 < num_phases(); ++i) {
    for (const PhaseLink& l : links_[i]) {
      b_x0(row, state_offset(i + 1) + l.to_state) = 1.0;
      b_xf(row, state_offset(i) + l.from_state) = -1.0;
      ++row;
    }
  }
  for (int i = 0; i + 1 < num_phases(); ++i) {
    const Ocp& p = phase(i);
    Vec psi(p.num_terminal());
    Mat psix(p.num_terminal(), p.nx());
    p.TerminalConstraintsJacobian(xf.segment(state_offset(i), p.nx()), psi, psix);
    b_xf.block(event_row_[i], state_offset(i), p.num_terminal(), p.nx()) = psix;
  }
  for (int i = 0; i < num_phases(); ++i) {
    const Ocp& p = phase(i);
    if (p.num_boundary() == 0) continue;
    Vec bi(p.num_boundary());
    Mat bi0(p.num_boundary(), p.nx()), bif(p.num_boundary(), p.nx());
    p.BoundaryConstraintsJacobian(
        x0.segment(state_offset(i), p.nx()), xf.segment(state_offset(i), p.nx()), bi, bi0, bif);
    b_x0.block(phase_boundary_row_[i], state_offset(i), p.num_boundary(), p.nx()) = bi0;
    b_xf.block(phase_boundary_row_[i], state_offset(i), p.num_boundary(), p.nx()) = bif;
  }
}

void MultiPhaseOcp::TerminalConstraintsJacobian(ConstVecRef x, VecRef psi, MatRef psix) const {
  const int last = num_phases() - 1;
  const Ocp& p = phase(last);
  psix.setZero();
  Mat block(p.num_terminal(), p.nx());
  p.TerminalConstraintsJacobian(x.segment(state_offset(last), p.nx()), psi, block);
  psix.block(0, state_offset(last), p.num_terminal(), p.nx()) = block;
}

void MultiPhaseOcp::PathConstraintsJacobian(
    double t, ConstVecRef x, ConstVecRef u, VecRef c, MatRef cx, MatRef cu) const {
  cx.setZero();
  cu.setZero();
  for (int i = 0; i < num_phases(); ++i) {
    const Ocp& p = phase(i);
    const int nc = p.num_path();
    if (nc == 0) continue;
    const int xo = state_offset(i), uo = control_offset(i), n = p.nx(), m = p.nu();
    Vec ci(nc);
    Mat cxi(nc, n), cui(nc, m);
    p.PathConstraintsJacobian(PhaseTime(i, t), x.segment(xo, n), u.segment(uo, m), ci, cxi, cui);
    c.segment(path_offset_[i], nc) = ci;
    cx.block(path_offset_[i], xo, nc, n) = cxi;
    cu.block(path_offset_[i], uo, nc, m) = cui;
  }
}

// ---- second derivatives ----------------------------------------------------------------

void MultiPhaseOcp::PointHessian(double t,
                                 ConstVecRef x,
                                 ConstVecRef u,
                                 double sigma,
                                 ConstVecRef lambda,
                                 ConstVecRef mu,
                                 MatRef hess) const {
  hess.setZero();
  const int NX = nx();
  for (int i = 0; i < num_phases(); ++i) {
    const Ocp& p = phase(i);
    const int xo = state_offset(i), uo = control_offset(i), n = p.nx(), m = p.nu();
    const int d = duration_index(i);
    const double T = x[d];
    const double ti = PhaseTime(i, t);
    const auto xi = x.segment(xo, n);
    const auto ui = u.segment(uo, m);
    const Vec lambda_i = lambda.segment(xo, n);
    const Vec mu_i = p.num_path() ? Vec(mu.segment(path_offset_[i], p.num_path())) : Vec();
    // T (sigma L_i + lambda_i^T f_i) + mu_i^T c_i in (x_i, u_i).
    Mat hi(n + m, n + m);
    p.PointHessian(ti, xi, ui, sigma * T, T * lambda_i, mu_i, hi);
    hess.block(xo, xo, n, n) = hi.topLeftCorner(n, n);
    hess.block(xo, NX + uo, n, m) = hi.topRightCorner(n, m);
    hess.block(NX + uo, xo, m, n) = hi.bottomLeftCorner(m, n);
    hess.block(NX + uo, NX + uo, m, m) = hi.bottomRightCorner(m, m);
    // The cross terms with T: d/dz_i of (sigma L_i + lambda_i^T f_i).
    Vec f(n), Lx(n), Lu(m);
    Mat fx(n, n), fu(n, m);
    double L = 0.0;
    p.DynamicsJacobian(ti, xi, ui, f, fx, fu);
    p.RunningCostGradient(ti, xi, ui, &L, Lx, Lu);
    const Vec gx = sigma * Lx + fx.transpose() * lambda_i;
    const Vec gu = sigma * Lu + fu.transpose() * lambda_i;
    hess.block(d, xo, 1, n) = gx.transpose();
    hess.block(xo, d, n, 1) = gx;
    hess.block(d, NX + uo, 1, m) = gu.transpose();
    hess.block(NX + uo, d, m, 1) = gu;
  }
}

void MultiPhaseOcp::TerminalHessian(ConstVecRef x,
                                    double sigma,
                                    ConstVecRef nu,
                                    MatRef hess) const {
  hess.setZero();
  const int last = num_phases() - 1;
  for (int i = 0; i < num_phases(); ++i) {
    const Ocp& p = phase(i);
    const int xo = state_offset(i), n = p.nx();
    Mat h(n, n);
    const Vec nu_i = i == last ? Vec(nu) : Vec(Vec::Zero(p.num_terminal()));
    p.TerminalHessian(x.segment(xo, n), sigma, nu_i, h);
    hess.block(xo, xo, n, n) = h;
  }
}

void MultiPhaseOcp::BoundaryHessian(ConstVecRef x0,
                                    ConstVecRef xf,
                                    ConstVecRef mu,
                                    MatRef hess) const {
  hess.setZero();
  const int NX = nx();
  // Links are linear; events are psi_i at x_i(end); each phase's own rows couple its ends.
  for (int i = 0; i + 1 < num_phases(); ++i) {
    const Ocp& p = phase(i);
    const int xo = state_offset(i), n = p.nx();
    if (p.num_terminal() == 0) continue;
    Mat h(n, n);
    p.TerminalHessian(xf.segment(xo, n), 0.0, mu.segment(event_row_[i], p.num_terminal()), h);
    hess.block(NX + xo, NX + xo, n, n) += h;
  }
  for (int i = 0; i < num_phases(); ++i) {
    const Ocp& p = phase(i);
    const int nb = p.num_boundary();
    if (nb == 0) continue;
    const int xo = state_offset(i), n = p.nx();
    Mat h(2 * n, 2 * n);
    p.BoundaryHessian(
        x0.segment(xo, n), xf.segment(xo, n), mu.segment(phase_boundary_row_[i], nb), h);
    hess.block(xo, xo, n, n) += h.topLeftCorner(n, n);
    hess.block(xo, NX + xo, n, n) += h.topRightCorner(n, n);
    hess.block(NX + xo, xo, n, n) += h.bottomLeftCorner(n, n);
    hess.block(NX + xo, NX + xo, n, n) += h.bottomRightCorner(n, n);
  }
}

void MultiPhaseOcp::InitialCostHessian(ConstVecRef x0, double sigma, MatRef hess) const {
  hess.setZero();
  for (int i = 0; i < num_phases(); ++i) {
    if (!CountsInitialCost(i)) continue;
    const Ocp& p = phase(i);
    const int xo = state_offset(i), n = p.nx();
    Mat h(n, n);
    p.InitialCostHessian(x0.segment(xo, n), sigma, h);
    hess.block(xo, xo, n, n) = h;
  }
}

}  // namespace ocpb
