// LU factorization with partial pivoting of small dense matrices, in plain loops on caller-owned
// column-major storage: the kernel of the Riccati sweep's interval blocks and of the Hamiltonian
// minimizer's derivative (a few thousand factorizations of 3 x 3 .. 10 x 10 matrices per Newton
// step, where Eigen's dynamic-size LU spends more in its dispatch and allocation than in the
// arithmetic).
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace ocpb {

/// The dimension of a small-matrix kernel: kN when kN > 0 (known at compile time, so the loops
/// unroll), else the runtime value n.
template <int kN>
constexpr int SmallDim(int n) {
  if constexpr (kN > 0) {
    return kN;
  } else {
    return n;
  }
}

/// Factors the n x n column-major matrix `a` (leading dimension n) in place as P A = L U, L unit
/// lower triangular, with partial pivoting; `pivot[j]` is the row swapped with row j at step j.
/// Returns false when a pivot is not finite or negligible: |pivot| <= 1e-13 max |pivot| (or 0).
/// kN > 0 fixes n at compile time (the argument n is then ignored).
template <int kN>
bool SmallLuFactor(double* a, int* pivot, int n_runtime) {
  const int n = SmallDim<kN>(n_runtime);
  double largest = 0.0;
  for (int j = 0; j < n; ++j) {
    double* col = a + j * n;
    int p = j;
    double best = std::abs(col[j]);
    for (int i = j + 1; i < n; ++i) {
      const double v = std::abs(col[i]);
      if (v > best) {
        best = v;
        p = i;
      }
    }
    if (!std::isfinite(best) || !(best > 0.0)) return false;
    pivot[j] = p;
    if (p != j) {
      for (int c = 0; c < n; ++c) std::swap(a[c * n + j], a[c * n + p]);
    }
    largest = std::max(largest, best);
    const double inv = 1.0 / col[j];
    for (int i = j + 1; i < n; ++i) col[i] *= inv;
    for (int c = j + 1; c < n; ++c) {
      double* other = a + c * n;
      const double v = other[j];
      for (int i = j + 1; i < n; ++i) other[i] -= col[i] * v;
    }
  }
  for (int j = 0; j < n; ++j) {
    if (!(std::abs(a[j * n + j]) > 1e-13 * largest)) return false;
  }
  return true;
}

/// x := A^-1 x with the factors of SmallLuFactor (x of length n).
template <int kN>
void SmallLuSolve(const double* lu, const int* pivot, int n_runtime, double* x) {
  const int n = SmallDim<kN>(n_runtime);
  for (int j = 0; j < n; ++j) {
    if (pivot[j] != j) std::swap(x[j], x[pivot[j]]);
  }
  for (int j = 0; j < n; ++j) {  // L (unit diagonal), column by column
    const double v = x[j];
    const double* col = lu + j * n;
    for (int i = j + 1; i < n; ++i) x[i] -= col[i] * v;
  }
  for (int j = n - 1; j >= 0; --j) {  // U
    const double* col = lu + j * n;
    x[j] /= col[j];
    const double v = x[j];
    for (int i = 0; i < j; ++i) x[i] -= col[i] * v;
  }
}

/// A runtime-size SmallLuFactor with its own storage (reused across calls of one size).
class SmallLu {
 public:
  /// Factors the n x n column-major matrix at `a` with leading dimension `lda`; false as
  /// SmallLuFactor.
  bool Compute(const double* a, int n, int lda) {
    n_ = n;
    lu_.resize(static_cast<size_t>(n) * n);
    pivot_.resize(n);
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) lu_[j * n + i] = a[j * lda + i];
    }
    return SmallLuFactor<0>(lu_.data(), pivot_.data(), n);
  }
  /// x := A^-1 x (x of length n), or each of `columns` columns of x (leading dimension ldx).
  void Solve(double* x) const { SmallLuSolve<0>(lu_.data(), pivot_.data(), n_, x); }
  void SolveColumns(double* x, int columns, int ldx) const {
    for (int c = 0; c < columns; ++c) Solve(x + c * ldx);
  }
  int size() const { return n_; }

 private:
  int n_ = 0;
  std::vector<double> lu_;
  std::vector<int> pivot_;
};

}  // namespace ocpb
