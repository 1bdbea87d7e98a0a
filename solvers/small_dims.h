// Compile-time dimensions for the small per-node kernels of the Newton polish.
#pragma once

namespace ocpb {

/// Calls `f.template operator()<kNx, kNu>()` with the problem's dimensions as compile-time
/// constants when the pair is compiled (nx in 1..6, nu in 1..3: every registered problem with a
/// Hamiltonian minimizer), else `f.template operator()<0, 0>()`, where 0 means "the runtime
/// value" (solvers/small_lu.h's SmallDim). The kernels' loops then unroll at the sizes that
/// occur; the runtime instantiation keeps every size working with the same code.
template <class F>
decltype(auto) WithSmallDims(int nx, int nu, F&& f) {
  auto by_nu = [&]<int kNx>() -> decltype(auto) {
    switch (nu) {
      case 1:
        return f.template operator()<kNx, 1>();
      case 2:
        return f.template operator()<kNx, 2>();
      case 3:
        return f.template operator()<kNx, 3>();
      default:
        return f.template operator()<0, 0>();
    }
  };
  switch (nx) {
    case 1:
      return by_nu.template operator()<1>();
    case 2:
      return by_nu.template operator()<2>();
    case 3:
      return by_nu.template operator()<3>();
    case 4:
      return by_nu.template operator()<4>();
    case 5:
      return by_nu.template operator()<5>();
    case 6:
      return by_nu.template operator()<6>();
    default:
      return f.template operator()<0, 0>();
  }
}

}  // namespace ocpb
