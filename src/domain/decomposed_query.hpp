// One rank's part of a decomposed contact search (domain/decomposition.hpp):
// the HGrid of the rank's own particles and its ghosts, filtered so that
// every overlapping pair is reported by exactly one rank.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "hgridlab/domain/decomposition.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/base/threads.hpp"

namespace hgrid {

/// What one rank's search did: the counters of its grid's query over its own
/// particles plus those of its ghosts' searches (the work this rank really
/// does), and the pairs it reported.
struct RankCounts {
  Counters work;
  std::uint64_t reported = 0;
};

/// Pass as the callback to count the reported pairs without handing them out
/// (no look-up of their global indices).
struct CountOnly {};

/// spheres: the rank's own particles (indices below n_owned), then its
/// ghosts; `grid` was built from the own ones only; `bricks` and `self` say
/// who owns what (domain/decomposition.hpp). Calls f(id_i, id_j), id_i < id_j,
/// for every overlapping pair whose lower particle in the reporting order
/// (radius, owner rank) is owned here, with ids[k] the global index of
/// spheres[k] (f(t, id_i, id_j) when it takes a thread index;
/// base/threads.hpp). With f = CountOnly only the reported pairs are
/// counted and ids may be empty.
///
/// Two own particles: the grid's query (no test on the pair, and with
/// CountOnly on a counted grid no callback at all). An own particle q and
/// a ghost g: reported here only if q comes first, so r_q <= r_g and q lies
/// on g's level of insertion or below: each ghost searches those levels of
/// the grid (HGrid::for_each_overlap_below). Two ghosts: never here.
template <Search S, class Count = Uncounted, int D, Boundary B, class F>
RankCounts query_reported_pairs(const HGrid<D, B>& grid, std::span<const Sphere<D>> spheres, std::size_t n_owned,
                                const Bricks<D>& bricks, int self, std::span<const std::uint64_t> ids, F&& f,
                                int threads) {
  (void)f;  // unused with CountOnly
  constexpr bool count_only = std::is_same_v<std::decay_t<F>, CountOnly>;
  if (n_owned != grid.size() || n_owned > spheres.size() || (!count_only && ids.size() != spheres.size()))
    throw InputError("ids", "one global index per particle, own particles (those of the grid) first");
  auto hand_out = [&](int t, std::size_t i, std::size_t j) {
    if constexpr (!count_only) {
      const std::uint64_t a = ids[i] < ids[j] ? ids[i] : ids[j];
      const std::uint64_t b = ids[i] < ids[j] ? ids[j] : ids[i];
      if constexpr (std::is_invocable_v<F&, int, std::uint64_t, std::uint64_t>)
        f(t, a, b);
      else
        f(a, b);
    }
  };
  RankCounts out;
  if constexpr (count_only && Count::enabled) {
    out.work = grid.template query<S, Count>([](std::uint32_t, std::uint32_t) {}, threads);
    out.reported = out.work.contacts;
  } else {
    const int T = resolve_threads(threads);
    std::vector<std::uint64_t> tally(static_cast<std::size_t>(T) * 8, 0);  // a cache line per thread
    out.work = grid.template query<S, Count>(
        [&](int t, std::uint32_t i, std::uint32_t j) {
          ++tally[static_cast<std::size_t>(t) * 8];
          hand_out(t, i, j);
        },
        threads);
    for (int t = 0; t < T; ++t) out.reported += tally[static_cast<std::size_t>(t) * 8];
  }
  // The ghosts' pairs, on one thread (a ghost is ~1 % of a rank's particles
  // at N = 10^7 on 2 ranks). The ghost's owner is looked up for a tie of
  // radii only.
  const auto ghosts = spheres.subspan(n_owned);
  out.work.add(grid.template for_each_overlap_below<Count>(ghosts, [&](std::uint32_t k, std::uint32_t q) {
    const std::size_t g = n_owned + k;
    const double rq = spheres[q].r, rg = spheres[g].r;
    if (!reports_before(rq, self, rg, rq == rg ? bricks.owner(spheres[g].x) : -1)) return;
    ++out.reported;
    hand_out(0, q, g);
  }));
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
