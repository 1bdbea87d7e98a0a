#include "core/rk_tableau.h"

#include <algorithm>
#include <cmath>

namespace ocpb {

RkTableau RkTableau::ForwardEuler() { return {"euler", 1, {0.0}, {1.0}, {0.0}}; }

RkTableau RkTableau::Heun() { return {"rk2", 2, {0.0, 0.0, 1.0, 0.0}, {0.5, 0.5}, {0.0, 1.0}}; }

RkTableau RkTableau::Classical4() {
  RkTableau t{"rk4",
              4,
              std::vector<double>(16, 0.0),
              {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6},
              {0.0, 0.5, 0.5, 1.0}};
  t.a[1 * 4 + 0] = 0.5;
  t.a[2 * 4 + 1] = 0.5;
  t.a[3 * 4 + 2] = 1.0;
  return t;
}

std::string RkTableau::Check() const {
  const size_t s = static_cast<size_t>(stages);
  if (stages < 1 || a.size() != s * s || b.size() != s || c.size() != s) {
    return "tableau '" + name + "': a must be s x s and b, c of size s (s >= 1)";
  }
  for (int i = 0; i < stages; ++i) {
    double row = 0.0;
    for (int j = 0; j < stages; ++j) {
      if (j >= i && A(i, j) != 0.0) {
        return "tableau '" + name + "' is not explicit (a_ij != 0 for j >= i)";
      }
      row += A(i, j);
    }
    if (std::abs(row - c[static_cast<size_t>(i)]) > 1e-14) {
      return "tableau '" + name + "': c_i must be sum_j a_ij";
    }
    if (!(b[static_cast<size_t>(i)] > 0.0)) {
      return "tableau '" + name +
             "': every b_i must be > 0 (the transformed adjoint divides by it)";
    }
  }
  return "";
}

std::vector<OrderCondition> HagerOrderConditions(const RkTableau& t) {
  const int s = t.stages;
  auto b = [&](int i) { return t.b[static_cast<size_t>(i)]; };
  auto c = [&](int i) { return t.c[static_cast<size_t>(i)]; };
  std::vector<double> d(static_cast<size_t>(s), 0.0);
  for (int j = 0; j < s; ++j) {
    for (int i = 0; i < s; ++i) d[static_cast<size_t>(j)] += b(i) * t.A(i, j);
  }
  auto D = [&](int i) { return d[static_cast<size_t>(i)]; };
  // Sums over one index and over two (i, j).
  auto sum1 = [&](auto term) {
    double v = 0.0;
    for (int i = 0; i < s; ++i) v += term(i);
    return v;
  };
  auto sum2 = [&](auto term) {
    double v = 0.0;
    for (int i = 0; i < s; ++i) {
      for (int j = 0; j < s; ++j) v += term(i, j);
    }
    return v;
  };
  std::vector<OrderCondition> out;
  auto add = [&](int order, const char* formula, double value, double expected) {
    out.push_back({order, formula, value, expected});
  };
  add(1, "sum b_i = 1", sum1([&](int i) { return b(i); }), 1.0);
  add(2, "sum d_i = 1/2", sum1([&](int i) { return D(i); }), 0.5);
  add(3, "sum c_i d_i = 1/6", sum1([&](int i) { return c(i) * D(i); }), 1.0 / 6);
  add(3, "sum b_i c_i^2 = 1/3", sum1([&](int i) { return b(i) * c(i) * c(i); }), 1.0 / 3);
  add(3, "sum d_i^2 / b_i = 1/3", sum1([&](int i) { return D(i) * D(i) / b(i); }), 1.0 / 3);
  add(4, "sum b_i c_i^3 = 1/4", sum1([&](int i) { return b(i) * std::pow(c(i), 3); }), 0.25);
  add(4,
      "sum b_i c_i a_ij c_j = 1/8",
      sum2([&](int i, int j) { return b(i) * c(i) * t.A(i, j) * c(j); }),
      1.0 / 8);
  add(4, "sum d_i c_i^2 = 1/12", sum1([&](int i) { return D(i) * c(i) * c(i); }), 1.0 / 12);
  add(4,
      "sum d_i a_ij c_j = 1/24",
      sum2([&](int i, int j) { return D(i) * t.A(i, j) * c(j); }),
      1.0 / 24);
  add(4,
      "sum c_i d_i^2 / b_i = 1/12",
      sum1([&](int i) { return c(i) * D(i) * D(i) / b(i); }),
      1.0 / 12);
  add(4,
      "sum d_i^3 / b_i^2 = 1/4",
      sum1([&](int i) { return std::pow(D(i), 3) / (b(i) * b(i)); }),
      0.25);
  add(4,
      "sum b_i c_i a_ij d_j / b_j = 5/24",
      sum2([&](int i, int j) { return b(i) * c(i) * t.A(i, j) * D(j) / b(j); }),
      5.0 / 24);
  add(4,
      "sum d_i a_ij d_j / b_j = 1/8",
      sum2([&](int i, int j) { return D(i) * t.A(i, j) * D(j) / b(j); }),
      1.0 / 8);
  return out;
}

int HagerOrder(const RkTableau& tableau, double tolerance) {
  int order = 4;
  for (const OrderCondition& oc : HagerOrderConditions(tableau)) {
    if (std::abs(oc.value - oc.expected) > tolerance) order = std::min(order, oc.order - 1);
  }
  return order;
}

}  // namespace ocpb
