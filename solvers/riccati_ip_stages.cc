#include "solvers/riccati_ip_stages.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "transcriptions/registry.h"

namespace ocpb::riccati_ip_internal {

std::unique_ptr<EulerStages> EulerStages::From(const TranscribedNlp& tnlp, std::string* why_not) {
  const auto* nlp = dynamic_cast<const CollocationNlp*>(&tnlp);
  if (nlp == nullptr) {
    *why_not =
        "riccati-ip takes the Euler and trapezoid transcriptions' NLPs only (not a collocation "
        "NLP)";
    return nullptr;
  }
  auto st = std::make_unique<EulerStages>(*nlp);
  const CollocationLayout& lay = nlp->layout();
  const Ocp& ocp = nlp->ocp();
  st->nx = ocp.nx();
  st->nu = ocp.nu();
  st->nc = ocp.num_path();
  st->hard = nlp->terminal_mode() == TerminalMode::kHard;
  st->npsi = st->hard ? ocp.num_terminal() : 0;
  // The trapezoid's shape: N + 1 nodes, each a point (t_k, x_k, u_k) with weight wt_k and
  // the path rows, defect k = x_{k+1} - x_k - a_k (f_k + f_{k+1}) with a_k = h_k / 2 > 0.
  const int nodes = static_cast<int>(lay.states.size());
  bool trapezoid = nodes >= 2 && static_cast<int>(lay.controls.size()) == nodes &&
                   static_cast<int>(lay.points.size()) == nodes &&
                   static_cast<int>(lay.defects.size()) == nodes - 1;
  for (int k = 0; trapezoid && k < nodes; ++k) {
    const auto& e = lay.points[k];
    trapezoid = e.state == k && e.control == k && e.path == (st->nc > 0) && e.cost_weight > 0.0;
    if (!trapezoid || k == nodes - 1) break;
    const auto& d = lay.defects[k];
    trapezoid = d.states.size() == 2 && d.states[0].index == k && d.states[0].coeff == -1.0 &&
                d.states[1].index == k + 1 && d.states[1].coeff == 1.0 && d.dynamics.size() == 2 &&
                d.dynamics[0].index == k && d.dynamics[1].index == k + 1 &&
                d.dynamics[0].coeff > 0.0 && d.dynamics[1].coeff == d.dynamics[0].coeff;
  }
  if (trapezoid) {
    st->trapezoid = true;
    st->N = nodes - 1;
    for (int k = 0; k < nodes; ++k) {
      st->t.push_back(lay.points[k].t);
      st->wt.push_back(lay.points[k].cost_weight);
      if (k + 1 < nodes) st->h.push_back(2.0 * lay.defects[k].dynamics[0].coeff);
    }
  }
  const int N = trapezoid ? nodes - 1 : static_cast<int>(lay.controls.size());
  st->N = N;
  // The Euler shape: N + 1 node states, N controls, defect k = x_{k+1} - x_k - h_k f(point k),
  // point k = (t_k, x_k, u_k) with weight h_k, and (path constraints) point N = (t_N, x_N,
  // u_{N-1}).
  bool euler = !trapezoid && N >= 1 && static_cast<int>(lay.states.size()) == N + 1 &&
               static_cast<int>(lay.defects.size()) == N &&
               static_cast<int>(lay.points.size()) == N + (st->nc > 0 ? 1 : 0);
  for (int k = 0; euler && k < N; ++k) {
    const auto& d = lay.defects[k];
    const auto& e = lay.points[k];
    euler = d.states.size() == 2 && d.states[0].index == k && d.states[0].coeff == -1.0 &&
            d.states[1].index == k + 1 && d.states[1].coeff == 1.0 && d.dynamics.size() == 1 &&
            d.dynamics[0].index == k && e.state == k && e.control == k &&
            d.dynamics[0].coeff == e.cost_weight && e.cost_weight > 0.0 && e.path == (st->nc > 0);
    if (euler) {
      st->t.push_back(e.t);
      st->h.push_back(e.cost_weight);
    }
  }
  if (trapezoid) {
    // (t, h, wt: above)
  } else if (euler && st->nc > 0) {
    const auto& e = lay.points[N];
    euler = e.state == N && e.control == N - 1 && e.cost_weight == 0.0 && e.path;
    st->t.push_back(e.t);
  } else if (euler) {
    st->t.push_back(lay.states[N].t);
  }
  if (!euler && !trapezoid) {
    *why_not =
        "riccati-ip takes the Euler and trapezoid transcriptions' NLPs only (this layout is "
        "another scheme)";
    return nullptr;
  }
  for (const auto& s : lay.states) st->state_off.push_back(s.offset);
  for (const auto& c : lay.controls) st->control_off.push_back(c.offset);
  st->lb = Vec::Constant(st->nu, -kRipInf);
  st->ub = Vec::Constant(st->nu, kRipInf);
  st->ufixed = Vec::Constant(st->nu, std::numeric_limits<double>::quiet_NaN());
  for (const auto& b : ocp.control_set().blocks()) {
    if (b.kind == ControlSet::Kind::kBall) {
      st->balls.push_back(b);
      continue;
    }
    for (int i = 0; i < b.size; ++i) {
      const double lo = b.lower[i], hi = b.upper[i];
      st->lb[b.offset + i] = lo <= -kRipInfBound ? -kRipInf : lo;
      st->ub[b.offset + i] = hi >= kRipInfBound ? kRipInf : hi;
      if (lo == hi) {  // fixed
        st->ufixed[b.offset + i] = lo;
        st->lb[b.offset + i] = -kRipInf;
        st->ub[b.offset + i] = kRipInf;
      }
    }
  }
  st->xlb = Vec::Constant(st->nx, -kRipInf);
  st->xub = Vec::Constant(st->nx, kRipInf);
  if (const auto& sb = ocp.state_bounds()) {
    for (int i = 0; i < st->nx; ++i) {
      const double lo = sb->lower[i], hi = sb->upper[i];
      st->xlb[i] = lo <= -kRipInfBound ? -kRipInf : lo;
      st->xub[i] = hi >= kRipInfBound ? kRipInf : hi;
      if (RipFinite(lo) && RipFinite(hi) && !(lo < hi)) {
        *why_not = "riccati-ip needs lower < upper for every bounded state (component " +
                   std::to_string(i) + " is fixed)";
        return nullptr;
      }
    }
  }
  const VectorBounds initial = ocp.InitialNodeBounds();
  st->x0lb = Vec::Constant(st->nx, -kRipInf);
  st->x0ub = Vec::Constant(st->nx, kRipInf);
  for (int i = 0; i < st->nx; ++i) {
    const double lo = initial.lower[i], hi = initial.upper[i];
    if (!(lo < hi)) continue;  // fixed: x0's value, no variable
    st->free0.push_back(i);
    st->x0lb[i] = lo <= -kRipInfBound ? -kRipInf : lo;
    st->x0ub[i] = hi >= kRipInfBound ? kRipInf : hi;
  }
  st->initial_cost = !st->free0.empty() && ocp.HasInitialCost();
  st->nb = ocp.num_boundary();
  if (st->nb > 0) {
    const VectorBounds& bb = ocp.boundary_bounds();
    st->blo = bb.lower;
    std::vector<double> lo, hi;
    for (int i = 0; i < st->nb; ++i) {
      if (bb.lower[i] == bb.upper[i]) continue;
      if (bb.lower[i] <= -kRipInfBound && bb.upper[i] >= kRipInfBound) {
        *why_not = "riccati-ip does not take a boundary row bounded on neither side (row " +
                   std::to_string(i) + ")";
        return nullptr;
      }
      st->bineq.push_back(i);
      st->blo[i] = 0.0;  // the row is b - s
      lo.push_back(bb.lower[i] <= -kRipInfBound ? -kRipInf : bb.lower[i]);
      hi.push_back(bb.upper[i] >= kRipInfBound ? kRipInf : bb.upper[i]);
    }
    st->sblo = Eigen::Map<const Vec>(lo.data(), st->nbi());
    st->sbhi = Eigen::Map<const Vec>(hi.data(), st->nbi());
  }
  if (tnlp.HasFinalTimeVariable()) {
    st->free_time = true;
    st->time_index = nlp->num_variables() - 1;  // T follows the layout's variables
    st->t0 = nlp->state_grid().t0();            // the nominal horizon (the Euler grid's ends)
    st->duration = nlp->state_grid().tf() - nlp->state_grid().t0();
    const double lo = ocp.free_final_time()->lower, hi = ocp.free_final_time()->upper;
    st->Tlb = Vec::Constant(1, lo <= -kRipInfBound ? -kRipInf : lo);
    st->Tub = Vec::Constant(1, hi >= kRipInfBound ? kRipInf : hi);
    if (!(lo < hi)) {
      *why_not = "riccati-ip needs lower < upper for a free final time";
      return nullptr;
    }
  }
  for (int j = 0; j < st->nu; ++j) {
    if (std::isnan(st->ufixed[j])) st->ufree.push_back(j);
  }
  st->nball = static_cast<int>(st->balls.size());
  st->relax_ball.assign(st->nball, 0.0);
  st->original = {
      st->lb, st->ub, st->xlb, st->xub, st->x0lb, st->x0ub, st->Tlb, st->Tub, st->sblo, st->sbhi};
  st->copy = st->nc > 0 && !st->trapezoid;
  return st;
}

void EulerStages::ToIterate(const Vec& z, Iterate* it) const {
  it->T.resize(nT(), nT());
  if (free_time) it->T(0, 0) = z[time_index];
  it->X.resize(nx, N + 1);
  it->U.resize(nu, nctl());
  for (int k = 0; k <= N; ++k) it->X.col(k) = z.segment(state_off[k], nx);
  for (int k = 0; k < nctl(); ++k) it->U.col(k) = z.segment(control_off[k], nu);
  for (int j = 0; j < nu; ++j) {
    if (!std::isnan(ufixed[j])) it->U.row(j).setConstant(ufixed[j]);
  }
  it->V = copy ? Vec(it->U.col(N - 1)) : Vec();
}

Vec EulerStages::ToNlp(const Iterate& it) const {
  Vec z = Vec::Zero(nlp.num_variables());
  for (int k = 0; k <= N; ++k) z.segment(state_off[k], nx) = it.X.col(k);
  for (int k = 0; k < nctl(); ++k) z.segment(control_off[k], nu) = it.U.col(k);
  if (free_time) z[time_index] = it.T(0, 0);
  return z;
}

void EulerStages::NodeInequalities(int k, const Iterate& it, VecRef c, Mat* cx, Mat* cu) const {
  const auto x = it.X.col(k);
  const auto u = StageControl(it, k);
  if (nc > 0) {
    if (cx != nullptr) {
      ocp.PathConstraintsJacobian(t[k], x, u, c.head(nc), cx->topRows(nc), cu->topRows(nc));
    } else {
      ocp.PathConstraints(t[k], x, u, c.head(nc));
    }
    c.head(nc).array() -= relax_path;
  }
  for (int b = 0; b < nball; ++b) {
    const auto& B = balls[b];
    double d2 = 0.0;
    for (int i = 0; i < B.size; ++i) {
      const double d = u[B.offset + i] - B.center[i];
      d2 += d * d;
      if (cu != nullptr) (*cu)(nc + b, B.offset + i) = 2.0 * d;
    }
    c[nc + b] = d2 - B.radius * B.radius - relax_ball[b];
  }
}

void EulerStages::EvalValues(const Iterate& it, Values* out) const {
  Values& v = *out;
  v.c.resize(N + 1);
  v.defects.resize(nx, N);
  Vec& f = f_scratch_;
  f.resize(nx);
  double J = 0.0;
  if (trapezoid) {  // node by node: f_k enters defects k - 1 and k
    Vec& f_prev = lam_scratch_;
    const double r = Rate(it);
    for (int k = 0; k <= N; ++k) {
      const auto x = it.X.col(k);
      const auto u = it.U.col(k);
      ocp.Dynamics(t[k], x, u, f);
      J += r * wt[k] * ocp.RunningCost(t[k], x, u);
      if (k > 0) v.defects.col(k - 1) = x - it.X.col(k - 1) - 0.5 * r * h[k - 1] * (f_prev + f);
      f_prev = f;
      v.c[k].resize(ni(k));
      NodeInequalities(k, it, v.c[k], nullptr, nullptr);
    }
  }
  for (int k = 0; k < N && !trapezoid; ++k) {
    const auto x = it.X.col(k);
    const auto u = it.U.col(k);
    ocp.Dynamics(t[k], x, u, f);
    const double hk = Step(it, k);
    J += hk * ocp.RunningCost(t[k], x, u);
    v.defects.col(k) = it.X.col(k + 1) - x - hk * f;
    Vec& c = v.c[k];
    c.resize(ni(k));
    if (nc > 0) {
      ocp.PathConstraints(t[k], x, u, c.head(nc));
      c.head(nc).array() -= relax_path;
    }
    for (int b = 0; b < nball; ++b) {
      const auto& B = balls[b];
      c[nc + b] = (u.segment(B.offset, B.size) - B.center).squaredNorm() - B.radius * B.radius -
                  relax_ball[b];
    }
  }
  if (!trapezoid) v.c[N].resize(ni(N));
  if (copy) {
    ocp.PathConstraints(t[N], it.X.col(N), it.V, v.c[N]);
    v.c[N].array() -= relax_path;
    v.copy_row = it.V - it.U.col(N - 1);
  }
  J += ocp.TerminalObjective(it.X.col(N), hard ? TerminalMode::kHard : TerminalMode::kPenalty);
  if (initial_cost) J += ocp.InitialCost(it.X.col(0));
  v.psi.resize(nterm());
  if (hard) ocp.TerminalConstraints(it.X.col(N), v.psi.head(npsi));
  if (nb > 0) {
    ocp.BoundaryConstraints(it.X.col(0), it.X.col(N), v.psi.tail(nb));
    v.psi.tail(nb) -= blo;
    for (int i = 0; i < nbi(); ++i) v.psi[npsi + bineq[i]] -= it.SB(i, 0);  // (blo: 0 there)
  }
  if (!copy) v.copy_row.resize(0);
  v.f = J;
  v.ok = RipFinite(J) && RipAllFinite(v.defects) && RipAllFinite(v.psi) && RipAllFinite(v.copy_row);
  for (const Vec& c : v.c) v.ok = v.ok && RipAllFinite(c);
}

bool EulerStages::EvalDerivatives(const Iterate& it,
                                  std::vector<StageEval>* stv,
                                  TerminalEval* te) const {
  auto& st = *stv;
  st.resize(N + 1);
  bool ok = true;
  for (int k = 0; k <= N; ++k) {
    StageEval& s = st[k];
    const auto x = it.X.col(k);
    const auto u = StageControl(it, k);
    const int m = ni(k);
    s.c.resize(m);
    s.cx.setZero(m, nx);
    s.cu.setZero(m, nu);
    if (k < N || trapezoid) {
      s.f.resize(nx);
      s.fx.resize(nx, nx);
      s.fu.resize(nx, nu);
      s.Lx.resize(nx);
      s.Lu.resize(nu);
      ocp.DynamicsJacobian(t[k], x, u, s.f, s.fx, s.fu);
      ocp.RunningCostGradient(t[k], x, u, &s.L, s.Lx, s.Lu);
      NodeInequalities(k, it, s.c, &s.cx, &s.cu);
      ok = ok && RipAllFinite(s.f) && RipAllFinite(s.fx) && RipAllFinite(s.fu) && RipFinite(s.L) &&
           RipAllFinite(s.Lx) && RipAllFinite(s.Lu);
      s.gT = free_time ? (trapezoid ? wt[k] : h[k]) / duration * s.L : 0.0;
    } else if (copy) {
      ocp.PathConstraintsJacobian(t[k], x, u, s.c, s.cx, s.cu);
      s.c.array() -= relax_path;
    }
    ok = ok && RipAllFinite(s.c) && RipAllFinite(s.cx) && RipAllFinite(s.cu);
  }
  const auto xN = it.X.col(N);
  te->grad.resize(nx);
  ocp.TerminalCostGradient(xN, &te->Phi, te->grad);
  if (ocp.num_terminal() > 0) {
    te->psi.resize(ocp.num_terminal());
    te->psix.resize(ocp.num_terminal(), nx);
    ocp.TerminalConstraintsJacobian(xN, te->psi, te->psix);
    if (!hard) {
      const Vec& w = ocp.terminal_weights();
      te->Phi += w.dot(te->psi.cwiseAbs2());
      te->grad += 2.0 * te->psix.transpose() * w.cwiseProduct(te->psi);
    }
  }
  ok = ok && RipFinite(te->Phi) && RipAllFinite(te->grad) && RipAllFinite(te->psi) &&
       RipAllFinite(te->psix);
  if (initial_cost) {
    te->grad0.resize(nx);
    ocp.InitialCostGradient(it.X.col(0), &te->Phi0, te->grad0);
    ok = ok && RipFinite(te->Phi0) && RipAllFinite(te->grad0);
  }
  if (nb > 0) {
    te->b.resize(nb);
    te->bx0.resize(nb, nx);
    te->bxN.resize(nb, nx);
    ocp.BoundaryConstraintsJacobian(it.X.col(0), xN, te->b, te->bx0, te->bxN);
    ok = ok && RipAllFinite(te->b) && RipAllFinite(te->bx0) && RipAllFinite(te->bxN);
  }
  return ok;
}

bool EulerStages::EvalHessians(const Iterate& it,
                               double sigma,
                               std::vector<StageEval>* stv,
                               TerminalEval* te) const {
  auto& st = *stv;
  bool ok = true;
  Vec& lam_f = lam_scratch_;
  for (int k = 0; k <= N; ++k) {
    StageEval& s = st[k];
    if (k == N && !copy && !trapezoid) break;
    s.H.resize(nx + nu, nx + nu);
    const auto x = it.X.col(k);
    const auto u = StageControl(it, k);
    const auto mu_path = it.y[k].head(nc);
    if (trapezoid) {      // f_k enters defects k - 1 and k with weights r h/2
      lam_f.setZero(nx);  // -(h_k/2 lam_k + h_{k-1}/2 lam_{k-1}), f_k's multiplier (unscaled)
      if (k < N) lam_f -= 0.5 * h[k] * it.lam.col(k);
      if (k > 0) lam_f -= 0.5 * h[k - 1] * it.lam.col(k - 1);
      if (free_time) {  // (1 / duration) (sigma wt_k L_k + lam_f^T f_k) differentiated in (x, u)
        s.HT.resize(nx + nu);
        s.HT.head(nx).noalias() = (sigma * wt[k] * s.Lx + s.fx.transpose() * lam_f) / duration;
        s.HT.tail(nu).noalias() = (sigma * wt[k] * s.Lu + s.fu.transpose() * lam_f) / duration;
      }
      const double r = Rate(it);
      lam_f *= r;
      ocp.PointHessian(t[k], x, u, sigma * r * wt[k], lam_f, mu_path, s.H);
      for (int b = 0; b < nball; ++b) {
        const auto& B = balls[b];
        s.H.diagonal().segment(nx + B.offset, B.size).array() += 2.0 * it.y[k][nc + b];
      }
    } else if (k < N) {
      const double hk = Step(it, k);
      lam_f = -hk * it.lam.col(k);
      ocp.PointHessian(t[k], x, u, sigma * hk, lam_f, mu_path, s.H);
      if (free_time) {  // (h_k / duration) (sigma L - lam^T f) differentiated in (x, u)
        const double a = h[k] / duration;
        s.HT.resize(nx + nu);
        s.HT.head(nx).noalias() = a * (sigma * s.Lx - s.fx.transpose() * it.lam.col(k));
        s.HT.tail(nu).noalias() = a * (sigma * s.Lu - s.fu.transpose() * it.lam.col(k));
      }
      for (int b = 0; b < nball; ++b) {
        const auto& B = balls[b];
        s.H.diagonal().segment(nx + B.offset, B.size).array() += 2.0 * it.y[k][nc + b];
      }
    } else {
      zero_scratch_.setZero(nx);
      ocp.PointHessian(t[k], x, u, 0.0, zero_scratch_, mu_path, s.H);
    }
    ok = ok && RipAllFinite(s.H);
  }
  te->H.resize(nx, nx);
  const auto xN = it.X.col(N);
  Vec nu_terms = Vec::Zero(ocp.num_terminal());
  if (hard) nu_terms = it.nu.head(npsi);
  if (!hard && ocp.num_terminal() > 0) {
    nu_terms = sigma * 2.0 * ocp.terminal_weights().cwiseProduct(te->psi);
  }
  ocp.TerminalHessian(xN, sigma, nu_terms, te->H);
  if (!hard && ocp.num_terminal() > 0) {
    te->H += 2.0 * sigma * te->psix.transpose() * ocp.terminal_weights().asDiagonal() * te->psix;
  }
  if (initial_cost) {
    te->H0.resize(nx, nx);
    ocp.InitialCostHessian(it.X.col(0), sigma, te->H0);
    ok = ok && RipAllFinite(te->H0);
  }
  if (nb > 0) {
    te->Hb.resize(2 * nx, 2 * nx);
    ocp.BoundaryHessian(it.X.col(0), xN, it.nu.tail(nb), te->Hb);
    ok = ok && RipAllFinite(te->Hb);
  }
  return ok && RipAllFinite(te->H);
}

void EulerStages::LagrangianGradient(const Iterate& it,
                                     double sigma,
                                     const std::vector<StageEval>& st,
                                     const TerminalEval& te,
                                     Mat* rx,
                                     Mat* ru,
                                     Vec* rv,
                                     double* rT) const {
  rx->resize(nx, N + 1);
  ru->resize(nu, nctl());
  *rT = 0.0;
  if (trapezoid) {
    rv->resize(0);
    Vec& m = lam_scratch_;  // h_k/2 lam_k + h_{k-1}/2 lam_{k-1}: f_k's multiplier (unscaled)
    const double r = Rate(it);
    for (int k = 0; k <= N; ++k) {
      const StageEval& s = st[k];
      m.setZero(nx);
      if (k < N) m += 0.5 * h[k] * it.lam.col(k);
      if (k > 0) m += 0.5 * h[k - 1] * it.lam.col(k - 1);
      if (free_time) *rT += sigma * s.gT - s.f.dot(m) / duration;
      auto gx = rx->col(k);
      auto gu = ru->col(k);
      gx.noalias() = r * (sigma * wt[k] * s.Lx - s.fx.transpose() * m);
      gu.noalias() = r * (sigma * wt[k] * s.Lu - s.fu.transpose() * m);
      if (k < N) gx -= it.lam.col(k);
      if (k > 0) gx += it.lam.col(k - 1);
      if (ni(k) > 0) {
        gx.noalias() += s.cx.transpose() * it.y[k];
        gu.noalias() += s.cu.transpose() * it.y[k];
      }
    }
    if (initial_cost) rx->col(0) += sigma * te.grad0;
    auto gN = rx->col(N);
    gN += sigma * te.grad;
    if (hard && npsi > 0) gN.noalias() += te.psix.transpose() * it.nu.head(npsi);
    if (nb > 0) {
      rx->col(0).noalias() += te.bx0.transpose() * it.nu.tail(nb);
      gN.noalias() += te.bxN.transpose() * it.nu.tail(nb);
    }
    return;
  }
  for (int k = 0; k < N; ++k) {
    const StageEval& s = st[k];
    const auto lam = it.lam.col(k);
    // Plain loops: the columns of f_x, f_u, c_x, c_u are a few entries long.
    double* gx = rx->col(k).data();
    double* gu = ru->col(k).data();
    const double* l = lam.data();
    const double* lp = k > 0 ? it.lam.col(k - 1).data() : nullptr;
    const double hk = Step(it, k);
    const double sh = sigma * hk;
    const int m = ni(k);
    if (free_time) *rT += sigma * s.gT - h[k] / duration * s.f.dot(lam);
    const double* y = m > 0 ? it.y[k].data() : nullptr;
    for (int j = 0; j < nx; ++j) {
      const double* fj = s.fx.data() + static_cast<long>(j) * nx;
      double d = 0.0;
      for (int i = 0; i < nx; ++i) d += fj[i] * l[i];
      double g = sh * s.Lx[j] - l[j] - hk * d;
      if (lp != nullptr) g += lp[j];
      const double* cj = s.cx.data() + static_cast<long>(j) * m;
      for (int i = 0; i < m; ++i) g += cj[i] * y[i];
      gx[j] = g;
    }
    for (int j = 0; j < nu; ++j) {
      const double* fj = s.fu.data() + static_cast<long>(j) * nx;
      double d = 0.0;
      for (int i = 0; i < nx; ++i) d += fj[i] * l[i];
      double g = sh * s.Lu[j] - hk * d;
      const double* cj = s.cu.data() + static_cast<long>(j) * m;
      for (int i = 0; i < m; ++i) g += cj[i] * y[i];
      gu[j] = g;
    }
  }
  if (initial_cost) rx->col(0) += sigma * te.grad0;
  auto gN = rx->col(N);
  gN = sigma * te.grad + it.lam.col(N - 1);
  if (hard && npsi > 0) gN.noalias() += te.psix.transpose() * it.nu.head(npsi);
  if (nb > 0) {
    rx->col(0).noalias() += te.bx0.transpose() * it.nu.tail(nb);
    gN.noalias() += te.bxN.transpose() * it.nu.tail(nb);
  }
  if (copy) {
    gN.noalias() += st[N].cx.transpose() * it.y[N];
    *rv = it.lamV;
    rv->noalias() += st[N].cu.transpose() * it.y[N];
    ru->col(N - 1) -= it.lamV;
  } else {
    rv->resize(0);
  }
}

}  // namespace ocpb::riccati_ip_internal
