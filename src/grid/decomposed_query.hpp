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
/// below n_owned), then its ghosts; `bricks` and `self` say who owns what
/// (grid/decomposition.hpp). Calls f(id_i, id_j), id_i < id_j, for every
/// overlapping pair whose lower particle in the reporting order (radius,
/// owner rank) is owned here, with ids[k] the global index of spheres[k]
/// (f(t, id_i, id_j) when it takes a thread index; grid/threads.hpp). With
/// f = CountOnly only the reported pairs are counted and ids may be empty.
template <Search S, class Count = Uncounted, int D, Boundary B, class F>
RankCounts query_reported_pairs(const HGrid<D, B>& grid, std::span<const Sphere<D>> spheres, std::size_t n_owned,
                                const Bricks<D>& bricks, int self, std::span<const std::uint64_t> ids, F&& f,
                                int threads) {
  (void)f;  // unused with CountOnly
  constexpr bool count_only = std::is_same_v<std::decay_t<F>, CountOnly>;
  if (spheres.size() != grid.size() || (!count_only && ids.size() != spheres.size()) || n_owned > spheres.size())
    throw InputError("ids", "one global index per particle of the grid, own particles first");
  const int T = resolve_threads(threads);
  // Counted: the grid counts every pair it finds, so only the pairs left to
  // another rank are counted here (a ghost is in few pairs). Otherwise the
  // reported ones. A cache line per thread.
  constexpr bool by_drops = count_only && Count::enabled;
  std::vector<std::uint64_t> tally(static_cast<std::size_t>(T) * 8, 0);
  RankCounts out;
  out.work = grid.template query<S, Count>(
      [&](int t, std::uint32_t i, std::uint32_t j) {
        // i < j (HGrid::query), so j is a ghost if either is. Two own
        // particles: reported here, no look-up needed (most pairs).
        if (j >= n_owned) [[unlikely]] {
          // Different owners (a ghost is never owned here): the lower one's
          // owner reports the pair; ghosts alone are left to their owners.
          // (The ghost's owner is looked up for a tie of radii only.)
          const double ri = spheres[i].r, rj = spheres[j].r;
          const bool mine = i < n_owned && reports_before(ri, self, rj, ri == rj ? bricks.owner(spheres[j].x) : -1);
          if (!mine) {
            if constexpr (by_drops) ++tally[static_cast<std::size_t>(t) * 8];
            return;
          }
        }
        if constexpr (!by_drops) ++tally[static_cast<std::size_t>(t) * 8];
        if constexpr (!count_only) {
          const std::uint64_t a = ids[i] < ids[j] ? ids[i] : ids[j];
          const std::uint64_t b = ids[i] < ids[j] ? ids[j] : ids[i];
          if constexpr (std::is_invocable_v<F&, int, std::uint64_t, std::uint64_t>)
            f(t, a, b);
          else
            f(a, b);
        }
      },
      threads);
  std::uint64_t n = 0;
  for (int t = 0; t < T; ++t) n += tally[static_cast<std::size_t>(t) * 8];
  if constexpr (by_drops)
    out.reported = out.work.contacts - n;
  else
    out.reported = n;
  return out;
}

/// The longest side of the bricks' box (the scale of ghost_reach's margin).
template <int D>
double longest_side(const Bricks<D>& bricks) {
  double longest = 0;
  for (double side : bricks.box()) longest = std::max(longest, side);
  return longest;
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
