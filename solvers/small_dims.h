// Compile-time dimensions for small per-node and per-stage kernels.
#pragma once

namespace ocpb {

namespace small_dims_detail {

// f.template operator()<kNx, k>() for the k in 1..kNu equal to nu, else the run-time form <0, 0>.
template <int kNx, int kNu, class F>
decltype(auto) ByNu(int nu, F& f) {
  if constexpr (kNu == 0) {
    return f.template operator()<0, 0>();
  } else {
    if (nu == kNu) return f.template operator()<kNx, kNu>();
    return ByNu<kNx, kNu - 1>(nu, f);
  }
}

template <int kNx, int kMaxNu, class F>
decltype(auto) ByNx(int nx, int nu, F& f) {
  if constexpr (kNx == 0) {
    return f.template operator()<0, 0>();
  } else {
    if (nx == kNx) return ByNu<kNx, kMaxNu>(nu, f);
    return ByNx<kNx - 1, kMaxNu>(nx, nu, f);
  }
}

}  // namespace small_dims_detail

/// Calls `f.template operator()<kNx, kNu>()` with the dimensions as compile-time constants when
/// 1 <= nx <= kMaxNx and 1 <= nu <= kMaxNu, else `f.template operator()<0, 0>()`, where 0 means
/// "the run-time value" (solvers/small_lu.h's SmallDim). The kernels' loops then unroll at the
/// sizes that occur; the run-time instantiation keeps every size working with the same code.
/// Each pair in range is one instantiation of f: keep the ranges to the sizes that occur.
template <int kMaxNx, int kMaxNu, class F>
decltype(auto) WithDimsUpTo(int nx, int nu, F&& f) {
  return small_dims_detail::ByNx<kMaxNx, kMaxNu>(nx, nu, f);
}

/// The Newton polish's per-node kernels: nx in 1..6, nu in 1..3 (every registered problem with a
/// Hamiltonian minimizer).
template <class F>
decltype(auto) WithSmallDims(int nx, int nu, F&& f) {
  return WithDimsUpTo<6, 3>(nx, nu, f);
}

}  // namespace ocpb
