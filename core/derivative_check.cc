#include "core/derivative_check.h"

#include <algorithm>
#include <cmath>

#include <sstream>

namespace ocpb {

Mat CentralJacobian(const std::function<Vec(const Vec&)>& fn, const Vec& x, double step) {
  const Vec f0 = fn(x);
  Mat jac(f0.size(), x.size());
  Vec xp = x;
  for (int i = 0; i < x.size(); ++i) {
    const double h = step * std::max(1.0, std::abs(x[i]));
    xp[i] = x[i] + h;
    const Vec fp = fn(xp);
    xp[i] = x[i] - h;
    const Vec fm = fn(xp);
    xp[i] = x[i];
    jac.col(i) = (fp - fm) / (2.0 * h);
  }
  return jac;
}

namespace {

double RelativeError(const Mat& analytic, const Mat& fd) {
  double worst = 0.0;
  for (int i = 0; i < fd.rows(); ++i) {
    for (int j = 0; j < fd.cols(); ++j) {
      const double e = std::abs(analytic(i, j) - fd(i, j)) / std::max(1.0, std::abs(fd(i, j)));
      worst = std::max(worst, std::isnan(e) ? INFINITY : e);
    }
  }
  return worst;
}

}  // namespace

DerivativeCheck CheckOcpDerivatives(const Ocp& ocp, double t, const Vec& x, const Vec& u,
                                    const Vec& lambda, const Vec& mu, const Vec& nu) {
  const int nx = ocp.nx(), nu_dim = ocp.nu(), npsi = ocp.num_terminal(), nc = ocp.num_path();
  const int nz = nx + nu_dim;
  DerivativeCheck check;
  std::ostringstream log;
  auto record = [&](const char* name, const Mat& analytic, const Mat& fd) {
    const double e = RelativeError(analytic, fd);
    check.max_error = std::max(check.max_error, e);
    log << name << ": " << e << "\n";
  };
  Vec z(nz);
  z << x, u;
  auto split = [&](const Vec& zz) { return std::make_pair(Vec(zz.head(nx)), Vec(zz.tail(nu_dim))); };

  // First derivatives.
  Vec f(nx), Lx(nx), Lu(nu_dim);
  Mat fx(nx, nx), fu(nx, nu_dim);
  ocp.DynamicsJacobian(t, x, u, f, fx, fu);
  double L;
  ocp.RunningCostGradient(t, x, u, &L, Lx, Lu);
  const Mat fd_f = CentralJacobian(
      [&](const Vec& zz) {
        auto [xx, uu] = split(zz);
        Vec out(nx);
        ocp.Dynamics(t, xx, uu, out);
        return out;
      },
      z);
  Mat f_z(nx, nz);
  f_z << fx, fu;
  record("f_(x,u)", f_z, fd_f);
  const Mat fd_L = CentralJacobian(
      [&](const Vec& zz) {
        auto [xx, uu] = split(zz);
        return Vec::Constant(1, ocp.RunningCost(t, xx, uu));
      },
      z);
  Mat L_z(1, nz);
  L_z << Lx.transpose(), Lu.transpose();
  record("L_(x,u)", L_z, fd_L);

  double phi;
  Vec phix(nx);
  ocp.TerminalCostGradient(x, &phi, phix);
  record("phi_x", phix.transpose(),
         CentralJacobian([&](const Vec& xx) { return Vec::Constant(1, ocp.TerminalCost(xx)); }, x));
  if (npsi > 0) {
    Vec psi(npsi);
    Mat psix(npsi, nx);
    ocp.TerminalConstraintsJacobian(x, psi, psix);
    record("psi_x", psix, CentralJacobian(
                              [&](const Vec& xx) {
                                Vec out(npsi);
                                ocp.TerminalConstraints(xx, out);
                                return out;
                              },
                              x));
  }
  if (nc > 0) {
    Vec c(nc);
    Mat cx(nc, nx), cu(nc, nu_dim);
    ocp.PathConstraintsJacobian(t, x, u, c, cx, cu);
    Mat c_z(nc, nz);
    c_z << cx, cu;
    record("c_(x,u)", c_z, CentralJacobian(
                               [&](const Vec& zz) {
                                 auto [xx, uu] = split(zz);
                                 Vec out(nc);
                                 ocp.PathConstraints(t, xx, uu, out);
                                 return out;
                               },
                               z));
  }

  // Second derivatives: differences of the analytic gradients of sigma L + lambda^T f + mu^T c.
  const double sigma = 0.7;
  Mat hess(nz, nz);
  ocp.PointHessian(t, x, u, sigma, lambda, mu, hess);
  const Mat fd_hess = CentralJacobian(
      [&](const Vec& zz) {
        auto [xx, uu] = split(zz);
        Vec ff(nx), lx(nx), lu(nu_dim);
        Mat ffx(nx, nx), ffu(nx, nu_dim);
        double l;
        ocp.DynamicsJacobian(t, xx, uu, ff, ffx, ffu);
        ocp.RunningCostGradient(t, xx, uu, &l, lx, lu);
        Vec g(nz);
        g << sigma * lx + ffx.transpose() * lambda, sigma * lu + ffu.transpose() * lambda;
        if (nc > 0) {
          Vec c(nc);
          Mat cx(nc, nx), cu(nc, nu_dim);
          ocp.PathConstraintsJacobian(t, xx, uu, c, cx, cu);
          g.head(nx) += cx.transpose() * mu;
          g.tail(nu_dim) += cu.transpose() * mu;
        }
        return g;
      },
      z);
  record("hessian_(x,u) of sigma L + lambda'f + mu'c", hess, fd_hess);

  Mat thess(nx, nx);
  ocp.TerminalHessian(x, sigma, nu, thess);
  const Mat fd_thess = CentralJacobian(
      [&](const Vec& xx) {
        double p;
        Vec g(nx);
        ocp.TerminalCostGradient(xx, &p, g);
        g *= sigma;
        if (npsi > 0) {
          Vec psi(npsi);
          Mat psix(npsi, nx);
          ocp.TerminalConstraintsJacobian(xx, psi, psix);
          g += psix.transpose() * nu;
        }
        return g;
      },
      x);
  record("terminal hessian of sigma phi + nu'psi", thess, fd_thess);
  check.log = log.str();
  return check;
}

}  // namespace ocpb
