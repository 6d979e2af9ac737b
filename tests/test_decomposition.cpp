// The decomposed search (domain/decomposition.hpp, domain/decomposed_query.hpp)
// with every rank simulated in this process, against the O(N^2) brute force:
// the union of what the ranks report is the serial pair SET, each pair once.
#include <gtest/gtest.h>

#include <map>

#include "hgridlab/domain/decomposed_query.hpp"
#include "support.hpp"

namespace hgrid::test {
namespace {

struct Simulated {
  std::vector<std::pair<std::uint64_t, std::uint64_t>> pairs;  // sorted, not deduplicated
  std::uint64_t ghosts = 0, shell_ghosts = 0;
  std::vector<std::uint64_t> owned;  // per rank
};

/// What P ranks report, each with its own particles and the ghosts the
/// others send it (the transport of src/mpi, done here with vectors).
template <int D, Boundary B, Search S>
Simulated simulate(const Scene<D>& s, const std::vector<double>& sizes, int P, int threads = 1) {
  const Bricks<D> bricks(s.box, P, B);
  double r_max = 0;
  for (const auto& q : s.spheres) r_max = std::max(r_max, q.r);
  // Each particle placed as the transport does: its owner and the ranks
  // that need it as a ghost, in one call.
  std::vector<std::vector<Sphere<D>>> sph(P), ghost_sph(P);
  std::vector<std::vector<std::uint64_t>> ids(P), ghost_ids(P);
  Simulated out;
  const double longest = longest_side(bricks);
  for (std::size_t k = 0; k < s.spheres.size(); ++k) {
    const auto& q = s.spheres[k];
    const int o = bricks.place(q.x, ghost_reach(q.r, longest), [&](int to) {
      ghost_sph[to].push_back(q);
      ghost_ids[to].push_back(k);
      ++out.ghosts;
    });
    EXPECT_EQ(o, bricks.owner(q.x));
    sph[o].push_back(q);
    ids[o].push_back(k);
  }
  for (int r = 0; r < P; ++r) {
    out.owned.push_back(ids[r].size());
    out.shell_ghosts += shell_ghost_count(bricks, std::span<const Sphere<D>>(sph[r]), r, r_max);
  }
  for (int r = 0; r < P; ++r) {
    const std::size_t n_owned = sph[r].size();
    sph[r].insert(sph[r].end(), ghost_sph[r].begin(), ghost_sph[r].end());
    ids[r].insert(ids[r].end(), ghost_ids[r].begin(), ghost_ids[r].end());
    const HGrid<D, B> grid(std::span<const Sphere<D>>(sph[r].data(), n_owned), s.box, GridParams{sizes, S});
    std::vector<std::vector<std::pair<std::uint64_t, std::uint64_t>>> per_thread(resolve_threads(threads));
    const RankCounts c = query_reported_pairs<S, Counted>(
        grid, std::span<const Sphere<D>>(sph[r]), n_owned, bricks, r, std::span<const std::uint64_t>(ids[r]),
        [&](int t, std::uint64_t a, std::uint64_t b) { per_thread[t].emplace_back(a, b); }, threads);
    std::uint64_t n = 0;
    for (const auto& v : per_thread) out.pairs.insert(out.pairs.end(), v.begin(), v.end()), n += v.size();
    EXPECT_EQ(c.reported, n);
    // Counting alone (no global indices) reports as many.
    EXPECT_EQ((query_reported_pairs<S, Counted>(grid, std::span<const Sphere<D>>(sph[r]), n_owned, bricks, r, {},
                                                 CountOnly{}, threads)
                   .reported),
              n);
    EXPECT_EQ(c.work.particles(), n_owned);
  }
  std::sort(out.pairs.begin(), out.pairs.end());
  return out;
}

template <int D, Boundary B>
std::vector<std::pair<std::uint64_t, std::uint64_t>> expected(const Scene<D>& s) {
  std::vector<std::pair<std::uint64_t, std::uint64_t>> out;
  for (const auto& [i, j] : brute_pairs<D, B>(s)) out.emplace_back(i, j);
  return out;
}

template <int D, Boundary B, Search S>
void sweep(std::size_t n, std::uint64_t seed) {
  for (double nu : {0.1, 0.6})
    for (double alpha : {0.0, -3.0})
      for (double omega : {1.0, 10.0, 100.0, 1000.0}) {
        ++seed;
        const auto s = random_scene<D>(n, nu, alpha, omega, B, seed);
        double rmin = 1e300, rmax = 0;
        for (const auto& p : s.spheres) rmin = std::min(rmin, p.r), rmax = std::max(rmax, p.r);
        const auto sizes = exponential_sizes(4, rmin, rmax);
        const auto expect = expected<D, B>(s);
        // 7 ranks: slabs (7 x 1 x 1) thinner than r_max; 8: a cube of bricks.
        for (int P : {1, 2, 3, 4, 7, 8}) {
          SCOPED_TRACE(::testing::Message() << "seed=" << seed << " d=" << D << " " << to_string(B) << " "
                                            << to_string(S) << " nu=" << nu << " alpha=" << alpha
                                            << " omega=" << omega << " ranks=" << P);
          const Simulated got = simulate<D, B, S>(s, sizes, P);
          ASSERT_EQ(std::adjacent_find(got.pairs.begin(), got.pairs.end()), got.pairs.end())
              << "a pair was reported twice";
          ASSERT_EQ(got.pairs, expect);
          // The level-aware layer never sends more than the 2 r_max shell.
          ASSERT_LE(got.ghosts, got.shell_ghosts);
        }
      }
}

/// HGrid::for_each_overlap_below against brute force: the grid holds the
/// first half of a scene, the second half probes it; every overlapping
/// (probe, particle) pair with r_particle <= r_probe must come out once,
/// and nothing that does not overlap or lies above the probe's level.
template <int D, Boundary B>
void probes_against_brute(std::uint64_t seed) {
  for (double omega : {1.0, 10.0, 1000.0}) {
    SCOPED_TRACE(::testing::Message() << "seed=" << seed << " d=" << D << " " << to_string(B) << " omega=" << omega);
    const auto s = random_scene<D>(600, 0.5, -3.0, omega, B, seed++);
    double rmin = 1e300, rmax = 0;
    for (const auto& p : s.spheres) rmin = std::min(rmin, p.r), rmax = std::max(rmax, p.r);
    const auto sizes = exponential_sizes(3, rmin, rmax);
    const std::size_t half = s.spheres.size() / 2;
    const std::span<const Sphere<D>> all(s.spheres);
    const HGrid<D, B> grid(all.first(half), s.box, GridParams{sizes, Search::top_down});
    std::vector<Pair> got;
    grid.for_each_overlap_below(all.subspan(half), [&](std::uint32_t k, std::uint32_t j) {
      got.emplace_back(static_cast<std::uint32_t>(half + k), j);
    });
    std::sort(got.begin(), got.end());
    ASSERT_EQ(std::adjacent_find(got.begin(), got.end()), got.end()) << "a pair came twice";
    const auto level = [&](double r) {  // level of insertion (Eq. 3), the top one for larger spheres
      std::size_t h = 0;
      while (h + 1 < sizes.size() && 2 * r > grid.sizes()[h]) ++h;
      return h;
    };
    std::vector<Pair> must;  // overlapping, the grid's particle no larger than the probe
    for (const auto& [i, j] : brute_pairs<D, B>(s)) {
      if (i < half && j >= half && s.spheres[i].r <= s.spheres[j].r) must.emplace_back(j, i);
      if (j < half && i >= half && s.spheres[j].r <= s.spheres[i].r) must.emplace_back(i, j);
    }
    std::sort(must.begin(), must.end());
    ASSERT_TRUE(std::includes(got.begin(), got.end(), must.begin(), must.end())) << "a pair was missed";
    for (const auto& [k, j] : got) {
      ASSERT_LT(j, half);
      ASSERT_LE(level(s.spheres[j].r), level(s.spheres[k].r));
      ASSERT_TRUE((detail::overlap<D, B>(s.spheres[k], s.spheres[j], s.box))) << k << " " << j;
    }
  }
}

TEST(Decomposition, ProbesAgainstBrute) {
  probes_against_brute<2, Boundary::walls>(900);
  probes_against_brute<2, Boundary::periodic>(910);
  probes_against_brute<3, Boundary::walls>(920);
  probes_against_brute<3, Boundary::periodic>(930);
}

TEST(Decomposition, D2Walls) { sweep<2, Boundary::walls, Search::top_down>(400, 100); }
TEST(Decomposition, D2Periodic) { sweep<2, Boundary::periodic, Search::bottom_up>(400, 200); }
TEST(Decomposition, D3WallsTopDown) { sweep<3, Boundary::walls, Search::top_down>(400, 300); }
TEST(Decomposition, D3WallsBottomUp) { sweep<3, Boundary::walls, Search::bottom_up>(400, 400); }
TEST(Decomposition, D3PeriodicTopDown) { sweep<3, Boundary::periodic, Search::top_down>(400, 500); }
TEST(Decomposition, D3PeriodicBottomUp) { sweep<3, Boundary::periodic, Search::bottom_up>(400, 600); }

// A particle larger than several bricks: omega = 1000 at a low packing
// fraction puts the largest sphere across most of the box; 27 ranks in 3D.
TEST(Decomposition, LargeParticleSpansBricks) {
  const auto s = random_scene<3>(2000, 0.3, -3.0, 1000.0, Boundary::periodic, 4242);
  double rmin = 1e300, rmax = 0;
  for (const auto& p : s.spheres) rmin = std::min(rmin, p.r), rmax = std::max(rmax, p.r);
  const Bricks<3> bricks(s.box, 27, Boundary::periodic);
  EXPECT_GT(2 * rmax, s.box[0] / bricks.dims()[0]) << "the test needs a particle wider than a brick";
  const auto expect = expected<3, Boundary::periodic>(s);
  for (int threads : {1, 3}) {
    const auto got = simulate<3, Boundary::periodic, Search::top_down>(s, exponential_sizes(6, rmin, rmax), 27,
                                                                       threads);
    EXPECT_EQ(got.pairs, expect) << "threads=" << threads;
  }
}

// The target: omega = 100, alpha = -3 at nu = 0.6: the level-aware
// layer sends at least 5 times fewer ghosts than one 2 r_max shell.
TEST(Decomposition, LevelAwareGhostsAtOmega100) {
  const auto s = random_scene<3>(20000, 0.6, -3.0, 100.0, Boundary::periodic, 31337);
  double rmin = 1e300, rmax = 0;
  for (const auto& p : s.spheres) rmin = std::min(rmin, p.r), rmax = std::max(rmax, p.r);
  const auto expect = expected<3, Boundary::periodic>(s);
  for (int P : {2, 4, 8}) {
    const auto got = simulate<3, Boundary::periodic, Search::top_down>(s, exponential_sizes(4, rmin, rmax), P);
    EXPECT_EQ(got.pairs, expect);
    EXPECT_GE(static_cast<double>(got.shell_ghosts), 5.0 * static_cast<double>(got.ghosts)) << "ranks=" << P;
  }
}

TEST(Decomposition, BricksAreClosestToCubes) {
  EXPECT_EQ((Bricks<3>({1, 1, 1}, 8, Boundary::periodic).dims()), (std::array<int, 3>{2, 2, 2}));
  EXPECT_EQ((Bricks<3>({4, 1, 1}, 4, Boundary::walls).dims()), (std::array<int, 3>{4, 1, 1}));
  const Bricks<2> six({1, 1}, 6, Boundary::walls);
  EXPECT_EQ(six.dims()[0] * six.dims()[1], 6);
  EXPECT_EQ((Bricks<3>({1, 1, 1}, 7, Boundary::walls).ranks()), 7);
  EXPECT_THROW(Bricks<3>({1, 1, 1}, 0, Boundary::walls), InputError);
  // Every centre has an owner, including those on the far wall.
  const Bricks<3> b({2, 2, 2}, 8, Boundary::walls);
  EXPECT_EQ(b.owner({2.0, 2.0, 2.0}), 7);
  EXPECT_EQ(b.owner({0.0, 0.0, 0.0}), 0);
}

}  // namespace
}  // namespace hgrid::test
