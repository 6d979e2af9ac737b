// The work of an HGrid build's sort beyond one pass per particle (a term of
// the time model, docs/MODEL.md section 9): the build moves the particles
// into coarse buckets (about kCoarseBucket particles each, per level), then
// radix-sorts the low key bits inside each bucket, 8 bits per pass
// (grid/detail/hgrid_build.hpp, grid/detail/radix.hpp).
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>

namespace hgrid {

struct LevelSortWork {
  int passes = 0;             // radix passes over each of the level's particles
  std::uint64_t buckets = 0;  // coarse buckets of the level
};

/// For a level of `cells` cells in a grid of `n` particles.
inline LevelSortWork level_sort_work(std::uint64_t cells, std::uint64_t n) {
  constexpr std::uint64_t kCoarseBucket = 4096;  // grid/detail/levels.hpp
  constexpr int kBitsPerPass = 8;
  const int coarse_bits = static_cast<int>(std::bit_width(n / kCoarseBucket));
  const int shift = std::max(0, static_cast<int>(std::bit_width(std::max<std::uint64_t>(cells, 1) - 1)) - coarse_bits);
  return {(shift + kBitsPerPass - 1) / kBitsPerPass, ((std::max<std::uint64_t>(cells, 1) - 1) >> shift) + 1};
}

/// Summed over the levels: particle-passes and bucket-passes of the sort.
struct SortWork {
  double particle_passes = 0, bucket_passes = 0;
};

}  // namespace hgrid
