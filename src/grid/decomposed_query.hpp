// One rank's part of a decomposed contact search (grid/decomposition.hpp):
// the HGrid of the rank's own particles and its ghosts, filtered so that
// every overlapping pair is reported by exactly one rank.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "grid/decomposition.hpp"
#include "grid/hgrid.hpp"
#include "grid/threads.hpp"

namespace hgrid {

/// What one rank's search did: the grid's counters over all its particles
/// (own and ghosts: the work this rank really does) and the pairs it reported.
struct RankCounts {
  Counters work;
  std::uint64_t reported = 0;
};

/// Pass as the callback to count the reported pairs without handing them out
/// (no look-up of their global indices).
struct CountOnly {};

/// `grid` was built from `spheres`: the rank's own particles first (indices
/// below n_owned), then its ghosts; ids[k] is the global index of spheres[k].
/// Calls f(id_i, id_j), id_i < id_j, for every overlapping pair whose lower
/// particle in the reporting order (radius, global index) is owned here
/// (f(t, id_i, id_j) when it takes a thread index; grid/threads.hpp).
template <Search S, class Count = Uncounted, int D, Boundary B, class F>
RankCounts query_reported_pairs(const HGrid<D, B>& grid, std::span<const Sphere<D>> spheres,
                                std::span<const std::uint64_t> ids, std::size_t n_owned, F&& f, int threads) {
  (void)f;  // unused with CountOnly
  if (spheres.size() != grid.size() || ids.size() != spheres.size() || n_owned > spheres.size())
    throw InputError("ids", "one global index per particle of the grid, own particles first");
  const int T = resolve_threads(threads);
  std::vector<std::uint64_t> reported(static_cast<std::size_t>(T) * 8, 0);  // a cache line per thread
  RankCounts out;
  out.work = grid.template query<S, Count>(
      [&](int t, std::uint32_t i, std::uint32_t j) {
        // Two own particles: reported here, no look-up needed (most pairs).
        if (i >= n_owned || j >= n_owned) {
          const bool i_first = reports_before(spheres[i].r, ids[i], spheres[j].r, ids[j]);
          if ((i_first ? i : j) >= n_owned) return;  // the lower one's owner reports it
        }
        ++reported[static_cast<std::size_t>(t) * 8];
        if constexpr (!std::is_same_v<std::decay_t<F>, CountOnly>) {
          const std::uint64_t a = ids[i] < ids[j] ? ids[i] : ids[j];
          const std::uint64_t b = ids[i] < ids[j] ? ids[j] : ids[i];
          if constexpr (std::is_invocable_v<F&, int, std::uint64_t, std::uint64_t>)
            f(t, a, b);
          else
            f(a, b);
        }
      },
      threads);
  for (int t = 0; t < T; ++t) out.reported += reported[static_cast<std::size_t>(t) * 8];
  return out;
}

/// The longest side of the bricks' box (the scale of ghost_reach's margin).
template <int D>
double longest_side(const Bricks<D>& bricks) {
  double longest = 0;
  for (double side : bricks.box()) longest = std::max(longest, side);
  return longest;
}

/// The ghosts a rank sends: for every own particle, the other ranks whose
/// bricks come within ghost_reach(r) of its centre; f(k, rank) for the k-th
/// of `own`.
template <int D, class F>
void for_each_ghost(const Bricks<D>& bricks, std::span<const Sphere<D>> own, int self, F&& f) {
  const double longest = longest_side(bricks);
  for (std::size_t k = 0; k < own.size(); ++k)
    bricks.for_each_within(own[k].x, ghost_reach(own[k].r, longest), self, [&](int rank) { f(k, rank); });
}

/// How many copies one shell of ghost_reach(r_max) for every particle would
/// send instead (what the level-aware layer is compared with).
template <int D>
std::uint64_t shell_ghost_count(const Bricks<D>& bricks, std::span<const Sphere<D>> own, int self, double r_max) {
  const double shell = ghost_reach(r_max, longest_side(bricks));
  std::uint64_t copies = 0;
  for (const auto& s : own) bricks.for_each_within(s.x, shell, self, [&](int) { ++copies; });
  return copies;
}

}  // namespace hgrid
