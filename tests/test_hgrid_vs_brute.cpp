// The HGrid against the O(N^2) brute force: identical pair SETS, no duplicates.
#include <gtest/gtest.h>

#include <tuple>

#include "support.hpp"

namespace hgrid::test {
namespace {

// (alpha, omega, L) grid swept for every (d, boundary, search).
const double kAlphas[] = {0.0, -1.0, -2.0, -3.0, -4.0};
const double kOmegas[] = {1.0, 1.0 + 1e-9, 2.0, 10.0, 100.0, 1000.0};
const int kLevels[] = {1, 2, 3, 5, 8, 12};
// Packing fractions: sparse to overlapping-dense (random centres overlap a lot).
const double kNus[] = {0.1, 0.6};

template <int D, Boundary B, Search S>
void sweep(std::size_t n) {
  std::uint64_t seed = 1000 * D + 10 * static_cast<int>(B) + static_cast<int>(S);
  for (double nu : kNus)
    for (double alpha : kAlphas)
      for (double omega : kOmegas)
        for (int L : kLevels) {
          ++seed;
          const auto s = random_scene<D>(n, nu, alpha, omega, B, seed);
          double rmin = 1e300, rmax = 0;
          for (const auto& p : s.spheres) rmin = std::min(rmin, p.r), rmax = std::max(rmax, p.r);
          const auto sizes = exponential_sizes(L, rmin, rmax);
          const auto expect = brute_pairs<D, B>(s);
          const auto [got, c] = grid_pairs<D, B, S, Counted>(s, sizes);
          SCOPED_TRACE(::testing::Message() << "seed=" << seed << " d=" << D << " " << to_string(B) << " "
                                            << to_string(S) << " nu=" << nu << " alpha=" << alpha
                                            << " omega=" << omega << " L=" << L);
          ASSERT_EQ(std::adjacent_find(got.begin(), got.end()), got.end()) << "a pair was reported twice";
          ASSERT_EQ(got, expect);
          ASSERT_EQ(c.contacts, expect.size());
          ASSERT_EQ(c.particles(), n);
          // Every reported pair was a candidate: the checks bound the contacts.
          ASSERT_GE(c.narrow_phase_checks, c.contacts);
        }
}

TEST(HGridVsBrute, D2WallsTopDown) { sweep<2, Boundary::walls, Search::top_down>(300); }
TEST(HGridVsBrute, D2WallsBottomUp) { sweep<2, Boundary::walls, Search::bottom_up>(300); }
TEST(HGridVsBrute, D2PeriodicTopDown) { sweep<2, Boundary::periodic, Search::top_down>(300); }
TEST(HGridVsBrute, D2PeriodicBottomUp) { sweep<2, Boundary::periodic, Search::bottom_up>(300); }
TEST(HGridVsBrute, D3WallsTopDown) { sweep<3, Boundary::walls, Search::top_down>(300); }
TEST(HGridVsBrute, D3WallsBottomUp) { sweep<3, Boundary::walls, Search::bottom_up>(300); }
TEST(HGridVsBrute, D3PeriodicTopDown) { sweep<3, Boundary::periodic, Search::top_down>(300); }
TEST(HGridVsBrute, D3PeriodicBottomUp) { sweep<3, Boundary::periodic, Search::bottom_up>(300); }

// Larger packings with realistic level counts, fewer combinations.
TEST(HGridVsBrute, LargerPackings) {
  std::uint64_t seed = 77;
  for (double alpha : {0.0, -3.0})
    for (double omega : {10.0, 100.0}) {
      const auto s = random_scene<3>(4000, 0.5, alpha, omega, Boundary::periodic, ++seed);
      double rmax = 0;
      for (const auto& p : s.spheres) rmax = std::max(rmax, p.r);
      const auto expect = brute_pairs<3, Boundary::periodic>(s);
      for (int L : {1, 4, 7}) {
        SCOPED_TRACE(::testing::Message() << "seed=" << seed << " alpha=" << alpha << " omega=" << omega << " L=" << L);
        const auto sizes = exponential_sizes(L, 1.0, rmax);
        EXPECT_EQ((grid_pairs<3, Boundary::periodic, Search::top_down>(s, sizes).first), expect);
        EXPECT_EQ((grid_pairs<3, Boundary::periodic, Search::bottom_up>(s, sizes).first), expect);
      }
    }
}

// N above twice the construction's coarse bucket (detail::kCoarseBucket),
// so that its first sorting step spreads every level over several buckets
// (the packings above fit in one bucket per level).
TEST(HGridVsBrute, SeveralCoarseBuckets) {
  static_assert(detail::kCoarseBucket * 2 <= 12000, "the scenes below must span several coarse buckets");
  const auto s3 = random_scene<3>(12000, 0.5, -3.0, 100.0, Boundary::periodic, 9001);
  const auto e3 = brute_pairs<3, Boundary::periodic>(s3);
  const auto s2 = random_scene<2>(12000, 0.5, 0.0, 10.0, Boundary::walls, 9002);
  const auto e2 = brute_pairs<2, Boundary::walls>(s2);
  for (int L : {1, 3, 8}) {
    SCOPED_TRACE(::testing::Message() << "seeds 9001/9002, L=" << L);
    const auto z3 = exponential_sizes(L, 1.0, 100.0), z2 = exponential_sizes(L, 1.0, 10.0);
    EXPECT_EQ((grid_pairs<3, Boundary::periodic, Search::top_down>(s3, z3).first), e3);
    EXPECT_EQ((grid_pairs<3, Boundary::periodic, Search::bottom_up>(s3, z3).first), e3);
    EXPECT_EQ((grid_pairs<2, Boundary::walls, Search::top_down>(s2, z2).first), e2);
    EXPECT_EQ((grid_pairs<2, Boundary::walls, Search::bottom_up>(s2, z2).first), e2);
  }
}

// Sizes need not follow any rule: irregular, far apart, far above 2 r_max.
TEST(HGridVsBrute, IrregularSizes) {
  const auto s = random_scene<3>(800, 0.4, -2.0, 20.0, Boundary::periodic, 4242);
  const auto expect = brute_pairs<3, Boundary::periodic>(s);
  for (const std::vector<double>& sizes :
       {std::vector<double>{2.0, 2.1, 40.0}, std::vector<double>{3.3, 41.0, 500.0}, std::vector<double>{40.0, 1e4}}) {
    EXPECT_EQ((grid_pairs<3, Boundary::periodic, Search::top_down>(s, sizes).first), expect);
    EXPECT_EQ((grid_pairs<3, Boundary::periodic, Search::bottom_up>(s, sizes).first), expect);
  }
  const auto w = random_scene<3>(800, 0.4, -2.0, 20.0, Boundary::walls, 4243);
  const auto expect_w = brute_pairs<3, Boundary::walls>(w);
  EXPECT_EQ((grid_pairs<3, Boundary::walls, Search::top_down>(w, {2.0, 2.1, 40.0, 1e4}).first), expect_w);
  EXPECT_EQ((grid_pairs<3, Boundary::walls, Search::bottom_up>(w, {2.0, 2.1, 40.0, 1e4}).first), expect_w);
}

// Counting is a pure observer: same pairs with and without counters.
TEST(HGridVsBrute, CountingDoesNotChangePairs) {
  const auto s = random_scene<3>(2000, 0.6, -3.0, 100.0, Boundary::periodic, 99);
  const auto sizes = exponential_sizes(4, 1.0, 100.0);
  const auto a = grid_pairs<3, Boundary::periodic, Search::top_down, Counted>(s, sizes);
  const auto b = grid_pairs<3, Boundary::periodic, Search::top_down, Uncounted>(s, sizes);
  EXPECT_EQ(a.first, b.first);
  EXPECT_EQ(b.second.cell_accesses, 0u);  // the uncounted build counts nothing
}

}  // namespace
}  // namespace hgrid::test
