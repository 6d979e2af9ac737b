// Degenerate and manufactured cases, and counts worked out by hand.
#include <gtest/gtest.h>

#include "hgridlab/base/error.hpp"
#include "support.hpp"

namespace hgrid::test {
namespace {

template <int D>
Scene<D> scene(std::vector<Sphere<D>> s, Extent<D> box) {
  return Scene<D>{std::move(s), box};
}

template <int D, Boundary B>
void expect_matches_brute(const Scene<D>& s, const std::vector<double>& sizes) {
  const auto expect = brute_pairs<D, B>(s);
  const auto td = grid_pairs<D, B, Search::top_down, Counted>(s, sizes);
  const auto bu = grid_pairs<D, B, Search::bottom_up, Counted>(s, sizes);
  EXPECT_EQ(td.first, expect);
  EXPECT_EQ(bu.first, expect);
}

TEST(HGridCases, EmptyAndSingle) {
  Scene<3> empty{{}, {10, 10, 10}};
  auto [p0, c0] = grid_pairs<3, Boundary::periodic, Search::top_down, Counted>(empty, {1.0, 2.0});
  EXPECT_TRUE(p0.empty());
  EXPECT_EQ(c0.cell_accesses, 0u);
  Scene<3> one{{{{5, 5, 5}, 1.0}}, {10, 10, 10}};
  auto [p1, c1] = grid_pairs<3, Boundary::walls, Search::top_down, Counted>(one, {2.0});
  EXPECT_TRUE(p1.empty());
  EXPECT_EQ(c1.narrow_phase_checks, 0u);
  EXPECT_EQ(c1.particles(), 1u);
}

TEST(HGridCases, CoincidentCentres) {
  const auto s = scene<3>({{{1, 1, 1}, 0.5}, {{1, 1, 1}, 0.5}, {{1, 1, 1}, 2.0}, {{4, 4, 4}, 0.5}}, {5, 5, 5});
  expect_matches_brute<3, Boundary::walls>(s, {1.0, 4.0});
  expect_matches_brute<3, Boundary::periodic>(s, {1.0, 4.0});
  EXPECT_EQ((brute_pairs<3, Boundary::walls>(s).size()), 3u);
}

// Centres exactly on cell faces and on the box faces (0 and A).
TEST(HGridCases, OnCellAndBoxFaces) {
  std::vector<Sphere<2>> s;
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 8; ++j) s.push_back({{i * 1.0, j * 1.0}, (i + j) % 3 == 0 ? 0.55 : 0.45});
  s.push_back({{4.0, 4.0}, 1.9});
  s.push_back({{8.0, 0.0}, 1.5});
  const auto sc = scene<2>(s, {8, 8});
  for (const std::vector<double>& sizes : {std::vector<double>{1.0, 2.0, 4.0}, {2.0, 4.0}, {4.0}, {1.1, 3.8}}) {
    expect_matches_brute<2, Boundary::walls>(sc, sizes);
    // Periodic: x = 8 wraps onto x = 0, making coincident centres as well.
    expect_matches_brute<2, Boundary::periodic>(sc, sizes);
  }
}

// Periodic levels with 1 or 2 cells per axis: big search boxes wrap onto
// themselves; every pair must still come exactly once.
TEST(HGridCases, PeriodicFewCellsPerAxis) {
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    auto s = random_scene<3>(60, 0.5, -1.0, 8.0, Boundary::periodic, seed);
    double rmax = 0;
    for (const auto& p : s.spheres) rmax = std::max(rmax, p.r);
    const double A = s.box[0];
    SCOPED_TRACE(::testing::Message() << "seed=" << seed);
    // Level 2 with 2 (or 1) cells per axis, level 3 with 1; level 1 fine.
    const double mid = std::max(2 * rmax, 0.34 * A);
    expect_matches_brute<3, Boundary::periodic>(s, {2.0, mid, mid + 0.2 * A});
    expect_matches_brute<3, Boundary::periodic>(s, {2.0, 2 * A});
    auto s2 = random_scene<2>(40, 0.5, -2.0, 8.0, Boundary::periodic, seed);
    rmax = 0;
    for (const auto& p : s2.spheres) rmax = std::max(rmax, p.r);
    expect_matches_brute<2, Boundary::periodic>(s2, {2 * rmax, 3 * rmax, 1e3 * rmax});
  }
}

TEST(HGridCases, PeriodicMinimumImage) {
  // Overlap only across the periodic face.
  const auto s = scene<2>({{{0.2, 5}, 0.5}, {{9.9, 5}, 0.5}, {{5, 9.95}, 0.3}, {{5, 0.05}, 0.3}}, {10, 10});
  const auto expect = brute_pairs<2, Boundary::periodic>(s);
  ASSERT_EQ(expect.size(), 2u);
  expect_matches_brute<2, Boundary::periodic>(s, {1.0});
  expect_matches_brute<2, Boundary::periodic>(s, {1.0, 3.0});
  EXPECT_TRUE((brute_pairs<2, Boundary::walls>(s).empty()));
}

TEST(HGridCases, TouchingIsNotOverlapping) {
  // Distance exactly r_i + r_j: not reported (strict inequality).
  const auto s = scene<2>({{{1, 1}, 0.5}, {{2, 1}, 0.5}}, {4, 4});
  EXPECT_TRUE((grid_pairs<2, Boundary::walls, Search::top_down>(s, {1.0}).first.empty()));
}

// ---- counts worked out by hand (see README, "Counting semantics") ----------

// 2D, box 4 x 4, one level s = 2 (2 x 2 cells). Half stencil in 2D:
// (+1,-1), (+1,0), (+1,+1), (0,+1). Particles 0, 1 in cell (0,0), 2 in (1,0), 3 in (1,1).
Scene<2> four_particles() {
  return scene<2>({{{0.5, 0.5}, 0.5}, {{1.4, 0.5}, 0.5}, {{2.5, 0.5}, 0.5}, {{2.5, 2.5}, 0.5}}, {4, 4});
}

TEST(HGridCounts, SingleLevelWalls) {
  // Accesses: cell (0,0) has 3 neighbours in the box -> particles 0, 1: 4 each;
  // cell (1,0) has 1 ((1,1)) -> 2; cell (1,1) none -> 1. Total 11.
  // Checks: p0 = 1 (p1) + 1 (cell (1,0)) + 1 (cell (1,1)); p1 = 2; p2 = 1; p3 = 0. Total 6.
  const auto [pairs, c] = grid_pairs<2, Boundary::walls, Search::top_down, Counted>(four_particles(), {2.0});
  EXPECT_EQ(c.cell_accesses, 11u);
  EXPECT_EQ(c.narrow_phase_checks, 6u);
  EXPECT_EQ(c.contacts, 1u);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], (Pair{0, 1}));
}

TEST(HGridCounts, SingleLevelPeriodicTwoCellsPerAxis) {
  // 2 cells per axis: a neighbour's direction is the sign of the index
  // difference. Cell (0,0) -> 3 neighbours, (1,0) -> 1, (1,1) -> 0, as with
  // walls here; and every one of the 6 pairs is checked exactly once.
  const auto [pairs, c] = grid_pairs<2, Boundary::periodic, Search::top_down, Counted>(four_particles(), {2.0});
  EXPECT_EQ(c.cell_accesses, 11u);
  EXPECT_EQ(c.narrow_phase_checks, 6u);
  EXPECT_EQ(c.contacts, 1u);
}

TEST(HGridCounts, PeriodicThreeCubedOnePerCell) {
  // 27 particles, one per cell of a periodic 3 x 3 x 3 grid: each accesses
  // 1 + 13 cells and checks the 13 neighbours' particles; 27 * 13 = C(27, 2).
  std::vector<Sphere<3>> s;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) s.push_back({{i + 0.5, j + 0.5, k + 0.5}, 0.25});
  const auto [pairs, c] = grid_pairs<3, Boundary::periodic, Search::top_down, Counted>(scene<3>(s, {3, 3, 3}), {1.0});
  EXPECT_EQ(c.cell_accesses, 27u * 14u);
  EXPECT_EQ(c.narrow_phase_checks, 351u);
  EXPECT_EQ(c.contacts, 0u);
}

// 2D walls, box 4 x 4, levels s = 1 (4 x 4 cells) and s = 4 (1 cell).
// B (r = 1.5) at (2,2) on level 2; small particles (r = 0.25) at (0.5,0.5), (3.5,3.5).
Scene<2> big_and_small() {
  return scene<2>({{{0.5, 0.5}, 0.25}, {{2.0, 2.0}, 1.5}, {{3.5, 3.5}, 0.25}}, {4, 4});
}

TEST(HGridCounts, CrossLevelTopDown) {
  // B scans level 1 over x,y in [0, 4] (beta = 1.5 + 0.5 = 2): all 16 cells, 2 checks.
  // B's own level: 1 cell, no neighbour inside the walls: 1 access.
  // Small at (0,0): 1 + 3 accesses; small at (3,3): 1 access. Total 22.
  const auto [pairs, c] = grid_pairs<2, Boundary::walls, Search::top_down, Counted>(big_and_small(), {1.0, 4.0});
  EXPECT_EQ(c.cell_accesses, 22u);
  EXPECT_EQ(c.narrow_phase_checks, 2u);
  EXPECT_EQ(c.contacts, 0u);
  ASSERT_EQ(c.levels, 2);
  EXPECT_EQ(c.particles_per_level, (std::vector<std::uint64_t>{2, 1}));
  // [h * L + j]: (1,1) same-level smalls, (2,1) B across, (2,2) B's own level.
  EXPECT_EQ(c.accesses_by_level, (std::vector<std::uint64_t>{5, 0, 16, 1}));
  EXPECT_EQ(c.checks_by_level, (std::vector<std::uint64_t>{0, 0, 2, 0}));
}

TEST(HGridCounts, CrossLevelBottomUp) {
  // Each small scans level 2 (one cell): 1 access, 1 check. Same-level as above.
  const auto [pairs, c] = grid_pairs<2, Boundary::walls, Search::bottom_up, Counted>(big_and_small(), {1.0, 4.0});
  EXPECT_EQ(c.accesses_by_level, (std::vector<std::uint64_t>{5, 2, 0, 1}));
  EXPECT_EQ(c.checks_by_level, (std::vector<std::uint64_t>{0, 2, 0, 0}));
  EXPECT_EQ(c.cell_accesses, 8u);
  EXPECT_EQ(c.narrow_phase_checks, 2u);
}

// ---- rejected input ---------------------------------------------------------

TEST(HGridInput, Rejected) {
  const auto s = four_particles();
  auto build = [&](std::vector<Sphere<2>> sp, std::vector<double> sizes) {
    HGrid<2, Boundary::walls> g(std::span<const Sphere<2>>(sp), s.box, GridParams{sizes, Search::top_down});
  };
  EXPECT_THROW(build(s.spheres, {}), InputError);
  EXPECT_THROW(build(s.spheres, {2.0, 1.5}), InputError);
  EXPECT_THROW(build(s.spheres, {2.0, 2.0}), InputError);
  EXPECT_THROW(build(s.spheres, {0.5}), InputError);  // below the largest diameter
  EXPECT_THROW(build(s.spheres, {std::nan("")}), InputError);
  auto bad = s.spheres;
  bad[1].r = 0;
  EXPECT_THROW(build(bad, {2.0}), InputError);
  bad = s.spheres;
  bad[2].x[0] = std::nan("");
  EXPECT_THROW(build(bad, {2.0}), InputError);
  bad = s.spheres;
  bad[3].x[1] = 4.01;  // outside the walls
  EXPECT_THROW(build(bad, {2.0}), InputError);
  // Periodic: outside centres are wrapped, not rejected.
  auto wrapped = s.spheres;
  wrapped[3].x[1] = 4.0 + 2.5;
  EXPECT_NO_THROW((HGrid<2, Boundary::periodic>(std::span<const Sphere<2>>(wrapped), s.box, GridParams{{2.0}})));
}

}  // namespace
}  // namespace hgrid::test
