// Pair loops over a packing through the HGrid (contact detection for the
// generators' relaxation and quality checks).
#pragma once
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "hgrid/hgrid.hpp"

namespace hgrid::detail {

/// Cell sizes for spheres with radii in [rmin, rmax]: doubling from 2 rmin up
/// to the largest diameter (exponential sizes of ratio 2; one level if
/// monodisperse). Cheap and within a few tens of per cent of the optimum.
inline std::vector<double> doubling_sizes(double rmin, double rmax) {
  std::vector<double> s{2 * rmin * (1 + 1e-9)};
  while (s.back() < 2 * rmax) s.push_back(std::min(2 * s.back(), 2 * rmax * (1 + 1e-9)));
  return s;
}

/// Calls f(i, j) for every pair of spheres closer than r_i + r_j. Bottom-Up:
/// each sphere scans at most 3^d cells per larger level, whatever the size
/// ratio (Top-Down would scan (2 + 2r/s)^d small cells per big sphere).
template <int D, Boundary B, class F>
void for_each_overlapping(std::span<const Sphere<D>> spheres, const Extent<D>& box, F&& f) {
  if (spheres.size() < 2) return;
  double lo = spheres[0].r, hi = lo;
  for (const auto& s : spheres) {
    lo = std::min(lo, s.r);
    hi = std::max(hi, s.r);
  }
  const HGrid<D, B> grid(spheres, box, GridParams{doubling_sizes(lo, hi), Search::bottom_up});
  grid.template query<Search::bottom_up>(f);
}

}  // namespace hgrid::detail
