// Largest-first random sequential addition (RSA) on an insertion grid.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "hgridlab/packing/detail/gen_common.hpp"
#include "hgridlab/grid/geometry.hpp"

namespace hgrid::detail {

/// Attempts per particle before RSA gives up (it has stalled: the free volume
/// left for that radius is too small to find by uniform trials).
inline constexpr std::uint64_t kRsaMaxAttempts = 20000;

/// Places the spheres of radius scale * radii[i], visiting i in `order`
/// (radii descending), each at the first uniform trial position that overlaps
/// no placed sphere (walls: at least its radius from every wall). Writes
/// pos[i*d + k] for the placed ones. Returns how many were placed (all, unless
/// one exhausted kRsaMaxAttempts). Where particles need many trials, their
/// trials run several at a time on `threads` threads (>= 1); the packing and
/// the generator's state afterwards are the same for any number.
std::size_t rsa_place(int d, Boundary b, const std::array<double, 3>& box, const std::vector<double>& radii,
                      const std::vector<std::uint32_t>& order, double scale, int threads, GenRng& rng,
                      std::vector<double>& pos, Progress& progress);

}  // namespace hgrid::detail
