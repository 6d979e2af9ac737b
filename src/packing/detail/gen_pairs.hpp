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
#include "hgridlab/contacts/pair_sum.hpp"

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

/// Neighbour lists in compressed rows: the partners j > i of sphere i (pairs
/// closer than r_i + r_j) are nbr[start[i]] .. nbr[start[i + 1] - 1], in
/// ascending order. The grid finds pairs in an order of its own, which
/// changes with its cell sizes, its traversal and its threads; lists in
/// canonical order make every sum over them (forces in the FIRE relaxation) a
/// function of the spheres only. The search and the sort run on `threads`.
template <int D, Boundary B>
void neighbour_lists(std::span<const Sphere<D>> spheres, const Extent<D>& box, std::vector<std::uint32_t>& start,
                     std::vector<std::uint32_t>& nbr, int threads = 1) {
  const std::size_t n = spheres.size();
  const int T = std::max(1, threads);
  PairSum ps(n);
  std::vector<std::vector<std::uint64_t>> found(static_cast<std::size_t>(T));
  for_each_overlapping<D, B>(
      spheres, box,
      [&](int t, std::uint32_t i, std::uint32_t j) { found[static_cast<std::size_t>(t)].push_back(ps.key(i, j)); }, T);
  ps.gather(found);
  ps.rows(start, nbr);
}

}  // namespace hgrid::detail
