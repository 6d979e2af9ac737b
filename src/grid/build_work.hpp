// The work of an HGrid build's sort beyond one pass per particle (a term of
// the time model, docs/MODEL.md section 9): the build moves the particles
// into coarse buckets (about kCoarseBucket particles each, per level), then
// radix-sorts the low key bits inside each bucket, 8 bits per pass
// (grid/detail/hgrid_build.hpp, base/radix.hpp).
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>

#include "hgridlab/grid/detail/levels.hpp"

namespace hgrid {

struct LevelSortWork {
  int shift = 0;              // low key bits sorted inside a coarse bucket (a bucket is 2^shift keys)
  int passes = 0;             // radix passes over each of the level's particles
  std::uint64_t buckets = 0;  // coarse buckets of the level
};

/// For a level of `cells` cells in a grid of `n` particles on `levels`
/// levels: the build's own rule (HGrid::build takes its shifts and bucket
/// counts from here).
inline LevelSortWork level_sort_work(std::uint64_t cells, std::uint64_t n, int levels) {
  constexpr int kBitsPerPass = 8;  // base/radix.hpp
  if (levels == 1 && n <= detail::kDirectParticles && cells <= detail::kDirectCellsPerParticle * n + detail::kDirectMinCells)
    return {0, 0, std::max<std::uint64_t>(cells, 1)};  // one counting sort over the cells, no radix pass
  const int coarse_bits = static_cast<int>(std::bit_width(n / detail::kCoarseBucket));
  const std::uint64_t last = std::max<std::uint64_t>(cells, 1) - 1;
  const int shift = std::max(0, static_cast<int>(std::bit_width(last)) - coarse_bits);
  return {shift, (shift + kBitsPerPass - 1) / kBitsPerPass, (last >> shift) + 1};
}

/// Summed over the levels: particle-passes and bucket-passes of the sort.
struct SortWork {
  double particle_passes = 0, bucket_passes = 0;
};

}  // namespace hgrid
