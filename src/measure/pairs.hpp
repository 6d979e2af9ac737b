// Every overlapping pair of a packing, found by its grid or by brute force,
// for any dimension and boundary (a tilted box too): what `hgrid pairs` and Python's `pairs`
// print or return.
#pragma once
#include <cstdint>
#include <span>

#include "hgridlab/grid/brute_force.hpp"
#include "hgridlab/grid/dispatch.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/grid/tilted.hpp"
#include "hgridlab/packing/packing.hpp"

namespace hgrid {

/// f(thread, i, j) for every overlapping pair i < j of p, found by the grid
/// of g on g.threads threads (each pair once, in no particular order).
template <class F>
void for_each_packing_pair(const Packing& p, const GridParams& g, F&& f) {
  dispatch(p.d, p.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    const auto spheres = p.spheres<D>();
    if (p.tilted()) {
      const TiltedHGrid<D> grid(spheres, p.tilted_box<D>(), g);
      grid.for_each_pair(f);
    } else {
      const HGrid<D, decltype(bnd)::value> grid(spheres, p.extent<D>(), g);
      grid.for_each_pair(f);
    }
  });
}

/// The same pairs by the O(N^2) brute force on one thread (thread 0).
template <class F>
void for_each_packing_pair_brute(const Packing& p, F&& f) {
  dispatch(p.d, p.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    const auto spheres = p.spheres<D>();
    const auto g = [&](std::uint32_t i, std::uint32_t j) { f(0, i, j); };
    if (p.tilted()) brute_force_pairs_tilted<D>(std::span<const Sphere<D>>(spheres), p.tilted_box<D>(), g);
    else brute_force_pairs<D, decltype(bnd)::value>(std::span<const Sphere<D>>(spheres), p.extent<D>(), g);
  });
}

}  // namespace hgrid
