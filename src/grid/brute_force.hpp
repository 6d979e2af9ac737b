// The O(N^2) reference: every pair tested, same callback interface as HGrid.
#pragma once
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "hgridlab/grid/geometry.hpp"

namespace hgrid {

/// Calls f(i, j), i < j, for every pair with distance < r_i + r_j (minimum
/// image in a periodic box). Returns the number of pairs tested.
template <int D, Boundary B, class F>
std::uint64_t brute_force_pairs(std::span<const Sphere<D>> spheres, const Extent<D>& box, F&& f) {
  std::vector<Sphere<D>> s(spheres.begin(), spheres.end());
  if constexpr (B == Boundary::periodic) {
    for (auto& p : s)
      for (int a = 0; a < D; ++a) p.x[a] = detail::wrap(p.x[a], box[a]);
  }
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (detail::overlap<D, B>(s[i], s[j], box)) f(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
  return n * (n - (n > 0)) / 2;
}

}  // namespace hgrid
