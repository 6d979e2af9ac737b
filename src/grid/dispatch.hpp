// From runtime (d, boundary) to the compile-time HGrid policies.
#pragma once
#include <type_traits>

#include "hgridlab/base/error.hpp"
#include "hgridlab/grid/geometry.hpp"

namespace hgrid {

template <int D>
using DimTag = std::integral_constant<int, D>;
template <Boundary B>
using BoundaryTag = std::integral_constant<Boundary, B>;

/// Calls `fn(DimTag<D>{}, BoundaryTag<B>{})` for the runtime d and boundary.
template <class Fn>
decltype(auto) dispatch(int d, Boundary b, Fn&& fn) {
  if (d == 2) {
    if (b == Boundary::walls) return fn(DimTag<2>{}, BoundaryTag<Boundary::walls>{});
    return fn(DimTag<2>{}, BoundaryTag<Boundary::periodic>{});
  }
  if (d == 3) {
    if (b == Boundary::walls) return fn(DimTag<3>{}, BoundaryTag<Boundary::walls>{});
    return fn(DimTag<3>{}, BoundaryTag<Boundary::periodic>{});
  }
  throw InputError("d", "must be 2 or 3");
}

}  // namespace hgrid
