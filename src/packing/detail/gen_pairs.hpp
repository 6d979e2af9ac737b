// Pair loops over a packing through the HGrid (contact detection for the
// generators' relaxation and quality checks).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/contacts/contact_list.hpp"  // doubling_sizes

namespace hgrid::detail {

/// Calls f(i, j) for every pair of spheres closer than r_i + r_j, on
/// `threads` threads (f as a grid query's callback: base/threads.hpp).
/// Bottom-Up: each sphere scans at most 3^d cells per larger level, whatever
/// the size ratio (Top-Down would scan (2 + 2r/s)^d small cells per big sphere).
template <int D, Boundary B, class F>
void for_each_overlapping(std::span<const Sphere<D>> spheres, const Extent<D>& box, F&& f, int threads = 1) {
  if (spheres.size() < 2) return;
  double lo = spheres[0].r, hi = lo;
  for (const auto& s : spheres) {
    lo = std::min(lo, s.r);
    hi = std::max(hi, s.r);
  }
  const HGrid<D, B> grid(spheres, box, GridParams{doubling_sizes(lo, hi), Search::bottom_up, threads});
  grid.template query<Search::bottom_up>(f);
}

}  // namespace hgrid::detail
