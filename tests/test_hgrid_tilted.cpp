// The HGrid of a tilted (triclinic) periodic box against the O(N^2) brute
// force with the lattice's images: identical pair SETS for tilts from 0 to
// LAMMPS's limit (half the edge they lean along), 2D and 3D, both search
// directions, 1 and 2 threads; zero tilt is the orthogonal grid, counts and all.
#include <gtest/gtest.h>

#include <random>

#include "hgridlab/grid/tilted.hpp"
#include "support.hpp"

namespace hgrid::test {
namespace {

/// A scene in a tilted box: radii from the power law, lengths for packing
/// fraction nu, centres uniform in the box (fractional coordinates), every
/// third moved by a lattice vector so that the grid must wrap it.
template <int D>
std::pair<std::vector<Sphere<D>>, TiltedBox<D>> tilted_scene(std::size_t n, double nu, double alpha, double omega,
                                                              const std::array<double, 3>& tilt_frac,
                                                              std::uint64_t seed) {
  const Scene<D> s = random_scene<D>(n, nu, alpha, omega, Boundary::periodic, seed);
  TiltedBox<D> box{s.box, {}};
  box.tilt[0] = tilt_frac[0] * box.length[0];  // xy leans b along a
  if constexpr (D == 3) {
    box.tilt[1] = tilt_frac[1] * box.length[0];  // xz: c along a
    box.tilt[2] = tilt_frac[2] * box.length[1];  // yz: c along b
  }
  std::mt19937_64 rng(seed ^ 0x9e3779b97f4a7c15ULL);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Sphere<D>> out = s.spheres;
  for (std::size_t i = 0; i < n; ++i) {
    std::array<double, D> f{};
    for (auto& v : f) v = u(rng);
    if (i % 3 == 0) f[i % D] += (i % 2 ? 1.0 : -2.0);  // another image of the same point
    out[i].x = box.cartesian(f);
  }
  return {out, box};
}

template <int D>
std::vector<Pair> brute_tilted(const std::vector<Sphere<D>>& s, const TiltedBox<D>& box) {
  std::vector<Pair> out;
  brute_force_pairs_tilted<D>(std::span<const Sphere<D>>(s), box,
                              [&](std::uint32_t i, std::uint32_t j) { out.emplace_back(i, j); });
  std::sort(out.begin(), out.end());
  return out;
}

template <int D, Search S>
std::pair<std::vector<Pair>, Counters> tilted_pairs(const std::vector<Sphere<D>>& s, const TiltedBox<D>& box,
                                                    const std::vector<double>& sizes, int threads) {
  const TiltedHGrid<D> grid(std::span<const Sphere<D>>(s), box, GridParams{sizes, S, threads});
  std::vector<std::vector<Pair>> per(static_cast<std::size_t>(threads));
  const Counters c = grid.template query<S, Counted>(
      [&](int t, std::uint32_t i, std::uint32_t j) { per[static_cast<std::size_t>(t)].emplace_back(i, j); }, threads);
  std::vector<Pair> out;
  for (const auto& p : per) out.insert(out.end(), p.begin(), p.end());
  std::sort(out.begin(), out.end());
  return {out, c};
}

template <int D>
std::vector<std::array<double, 3>> tilt_cases() {
  if constexpr (D == 2) return {{0.0, 0, 0}, {0.1, 0, 0}, {-0.25, 0, 0}, {0.5, 0, 0}, {-0.5, 0, 0}};
  else
    return {{0.0, 0.0, 0.0}, {0.1, 0.0, 0.0}, {0.0, 0.3, 0.0}, {0.0, 0.0, -0.4},
            {0.5, 0.5, 0.5}, {-0.5, 0.5, -0.5}, {0.25, -0.1, 0.45}};
}

template <int D, Search S>
void sweep(std::size_t n) {
  std::uint64_t seed = 5000 + 100 * D + static_cast<int>(S);
  for (const auto& tilt : tilt_cases<D>())
    for (double alpha : {0.0, -3.0})
      for (double omega : {1.0, 4.0})
        for (int L : {1, 3}) {
          ++seed;
          const auto [s, box] = tilted_scene<D>(n, 0.3, alpha, omega, tilt, seed);
          double rmin = 1e300, rmax = 0;
          for (const auto& p : s) rmin = std::min(rmin, p.r), rmax = std::max(rmax, p.r);
          const auto sizes = exponential_sizes(L, rmin, rmax);
          SCOPED_TRACE(::testing::Message() << "seed=" << seed << " d=" << D << " " << to_string(S) << " tilt=("
                                            << tilt[0] << "," << tilt[1] << "," << tilt[2] << ") alpha=" << alpha
                                            << " omega=" << omega << " L=" << L);
          ASSERT_LT(4 * rmax, box.min_width()) << "the scene must be wide enough for the minimum image";
          const auto expect = brute_tilted<D>(s, box);
          ASSERT_FALSE(expect.empty());
          for (int threads : {1, 2}) {
            const auto [got, c] = tilted_pairs<D, S>(s, box, sizes, threads);
            ASSERT_EQ(std::adjacent_find(got.begin(), got.end()), got.end()) << "a pair was reported twice";
            ASSERT_EQ(got, expect) << threads << " threads";
            ASSERT_EQ(c.contacts, expect.size());
            ASSERT_GE(c.narrow_phase_checks, c.contacts);
          }
        }
}

/// Wide size ratios (omega 10 and 100): sparse packings, so that the box
/// stays wider than 4 r_max at the largest tilts.
template <int D, Search S>
void wide_sweep() {
  std::uint64_t seed = 7000 + 100 * D + static_cast<int>(S);
  const std::vector<std::array<double, 3>> tilts =
      D == 2 ? std::vector<std::array<double, 3>>{{0.5, 0, 0}, {-0.25, 0, 0}}
             : std::vector<std::array<double, 3>>{{0.5, 0.5, 0.5}, {0.25, -0.1, 0.45}};
  for (const auto& tilt : tilts)
    for (double omega : {10.0, 100.0})
      for (int L : {1, 4}) {
        ++seed;
        const std::size_t n = D == 2 ? 2000 : 2500;  // the brute force's N^2 3^d images: seconds under ASan
        const auto [s, box] = tilted_scene<D>(n, D == 2 ? 0.1 : 0.005, -3.0, omega, tilt, seed);
        double rmin = 1e300, rmax = 0;
        for (const auto& p : s) rmin = std::min(rmin, p.r), rmax = std::max(rmax, p.r);
        SCOPED_TRACE(::testing::Message() << "seed=" << seed << " d=" << D << " " << to_string(S) << " tilt=("
                                          << tilt[0] << "," << tilt[1] << "," << tilt[2] << ") omega=" << omega
                                          << " L=" << L);
        ASSERT_LT(4 * rmax, box.min_width());
        const auto expect = brute_tilted<D>(s, box);
        ASSERT_FALSE(expect.empty());
        for (int threads : {1, 2}) {
          const auto [got, c] = tilted_pairs<D, S>(s, box, exponential_sizes(L, rmin, rmax), threads);
          ASSERT_EQ(got, expect) << threads << " threads";
          ASSERT_EQ(c.contacts, expect.size());
        }
      }
}

TEST(HGridTilted, WideRatiosD2TopDown) { wide_sweep<2, Search::top_down>(); }
TEST(HGridTilted, WideRatiosD2BottomUp) { wide_sweep<2, Search::bottom_up>(); }
TEST(HGridTilted, WideRatiosD3TopDown) { wide_sweep<3, Search::top_down>(); }
TEST(HGridTilted, WideRatiosD3BottomUp) { wide_sweep<3, Search::bottom_up>(); }

TEST(HGridTilted, D2TopDown) { sweep<2, Search::top_down>(500); }
TEST(HGridTilted, D2BottomUp) { sweep<2, Search::bottom_up>(500); }
TEST(HGridTilted, D3TopDown) { sweep<3, Search::top_down>(700); }
TEST(HGridTilted, D3BottomUp) { sweep<3, Search::bottom_up>(700); }

// Zero tilt is the orthogonal box: the same pairs and every count equal.
TEST(HGridTilted, ZeroTiltIsTheOrthogonalGrid) {
  const Scene<3> s = random_scene<3>(3000, 0.5, -3.0, 10.0, Boundary::periodic, 42);
  const auto sizes = exponential_sizes(4, 1.0, 10.0);
  const auto [want, wc] = grid_pairs<3, Boundary::periodic, Search::top_down, Counted>(s, sizes);
  const TiltedHGrid<3> grid(std::span<const Sphere<3>>(s.spheres), TiltedBox<3>::orthogonal(s.box),
                            GridParams{sizes, Search::top_down});
  EXPECT_EQ(grid.inflation(), 1.0);
  std::vector<Pair> got;
  const Counters gc = grid.query<Search::top_down, Counted>(
      [&](std::uint32_t i, std::uint32_t j) { got.emplace_back(i, j); }, 1);
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, want);
  expect_same_counters(gc, wc);
  const HGrid<3, Boundary::periodic> orth(std::span<const Sphere<3>>(s.spheres), s.box,
                                          GridParams{sizes, Search::top_down});
  EXPECT_EQ(grid.sizes(), orth.sizes());  // as fitted to the box
}

// Lees-Edwards: an offset and the offset plus a box length are one lattice.
TEST(HGridTilted, LeesEdwardsIsATilt) {
  const Extent<2> l{40.0, 30.0};
  const auto a = TiltedBox<2>::lees_edwards(l, 13.0);
  const auto b = TiltedBox<2>::lees_edwards(l, 13.0 + 3 * 40.0);
  const auto c = TiltedBox<2>::lees_edwards(l, 33.0);  // reduced to -7
  EXPECT_DOUBLE_EQ(a.tilt[0], 13.0);
  EXPECT_DOUBLE_EQ(b.tilt[0], 13.0);
  EXPECT_DOUBLE_EQ(c.tilt[0], -7.0);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Sphere<2>> s(400);
  for (auto& p : s) p = Sphere<2>{{u(rng) * 40.0, u(rng) * 30.0}, 0.5 + u(rng)};
  const auto expect = brute_tilted<2>(s, a);
  EXPECT_EQ(brute_tilted<2>(s, b), expect);
  const auto [got, cnt] = tilted_pairs<2, Search::top_down>(s, b, exponential_sizes(2, 0.5, 1.5), 1);
  EXPECT_EQ(got, expect);
  // Pairs across the sheared faces exist: the orthogonal box finds others.
  const auto orth = brute_tilted<2>(s, TiltedBox<2>::orthogonal(l));
  EXPECT_NE(orth, expect);
}

// The inflation is the map's largest stretch: 1 at zero tilt, and for a
// simple shear of strain g, (g + sqrt(g^2 + 4)) / 2.
TEST(HGridTilted, Inflation) {
  EXPECT_EQ((TiltedBox<3>{{10, 10, 10}, {}}).inflation(), 1.0);
  for (double g : {0.1, 0.5, 1.0}) {
    const TiltedBox<2> b{{10.0, 10.0}, {g * 10.0, 0, 0}};
    EXPECT_NEAR(b.inflation(), (g + std::sqrt(g * g + 4)) / 2, 1e-8);
  }
  const TiltedBox<3> t{{10, 12, 14}, {5, -5, 6}};
  EXPECT_GT(t.inflation(), 1.0);
  EXPECT_NEAR(t.width(2), 14.0, 1e-12);  // the z faces are not tilted
}

// Tilts beyond LAMMPS's limit and non-finite ones are refused; a box of
// any width within it is searched.
TEST(HGridTilted, RefusesTiltsBeyondLammpsLimit) {
  std::vector<Sphere<3>> s{{{1, 1, 1}, 5.0}, {{5, 5, 5}, 2.0}};
  EXPECT_NO_THROW(TiltedHGrid<3>(std::span<const Sphere<3>>(s), TiltedBox<3>{{20, 20, 20}, {10, 0, 0}}, GridParams{{10.0}}));
  EXPECT_THROW(TiltedHGrid<3>(std::span<const Sphere<3>>(s), TiltedBox<3>{{40, 40, 40}, {20.5, 0, 0}}, GridParams{{10.0}}),
               InputError);
  EXPECT_NO_THROW(TiltedHGrid<3>(std::span<const Sphere<3>>(s), TiltedBox<3>{{40, 40, 40}, {0, -20, 20}}, GridParams{{10.0}}));
  const TiltedBox<2> bad{{10, 10}, {std::nan(""), 0, 0}};
  std::vector<Sphere<2>> s2{{{1, 1}, 1.0}};
  EXPECT_THROW(TiltedHGrid<2>(std::span<const Sphere<2>>(s2), bad, GridParams{{2.0}}), InputError);
}

// How many shifts around the rounding a reach needs: none below half the
// narrowest width, one up to one and a half widths, two beyond.
TEST(HGridTilted, ImageReach) {
  const TiltedBox<2> box{{10.0, 10.0}, {5.0, 0, 0}};  // widths 8.94 (x faces), 10 (y faces)
  const double w = box.width(0);
  EXPECT_NEAR(w, 10 / std::sqrt(1.25), 1e-12);
  EXPECT_EQ(box.image_reach(0.49 * w)[0], 0);
  EXPECT_EQ(box.image_reach(0.49 * w)[1], 0);
  EXPECT_EQ(box.image_reach(0.51 * w)[0], 1);
  EXPECT_EQ(box.image_reach(1.49 * w)[0], 1);
  EXPECT_EQ(box.image_reach(1.51 * w)[0], 2);
}

/// Boxes narrower than four largest radii (down to a third of it): few,
/// large spheres, so that pairs reach through several lattice images; the
/// pair sets against the brute force (which tries 1 + ceil((r_i + r_j) / w)
/// shifts either side), 2D and 3D, both directions, 1 and 2 threads.
template <int D, Search S>
void narrow_sweep() {
  std::uint64_t seed = 9000 + 100 * D + static_cast<int>(S);
  int narrow_seen = 0, reach2_seen = 0;
  for (const auto& tilt : tilt_cases<D>())
    for (double width_over_4r : {0.9, 0.6, 0.35}) {
      ++seed;
      std::mt19937_64 rng(seed);
      std::uniform_real_distribution<double> u(0.0, 1.0);
      const double rmax = 1.0, side = width_over_4r * 4 * rmax;
      TiltedBox<D> box{};
      for (int k = 0; k < D; ++k) box.length[k] = side * (1 + 0.2 * k);
      box.tilt[0] = tilt[0] * box.length[0];
      if constexpr (D == 3) {
        box.tilt[1] = tilt[1] * box.length[0];
        box.tilt[2] = tilt[2] * box.length[1];
      }
      std::vector<Sphere<D>> s(D == 2 ? 60 : 80);
      for (std::size_t i = 0; i < s.size(); ++i) {
        std::array<double, D> f{};
        for (auto& v : f) v = u(rng) + (i % 4 == 0 ? -1.0 : 0.0);  // some in another image
        s[i].x = box.cartesian(f);
        s[i].r = i == 0 ? rmax : 0.2 + 0.8 * u(rng);
      }
      SCOPED_TRACE(::testing::Message() << "seed=" << seed << " d=" << D << " " << to_string(S) << " tilt=("
                                        << tilt[0] << "," << tilt[1] << "," << tilt[2] << ") width "
                                        << box.min_width() << " for 4 r_max = " << 4 * rmax);
      if (box.min_width() < 4 * rmax) ++narrow_seen;
      const auto reach = box.image_reach(2 * rmax);
      if (*std::max_element(reach.begin(), reach.end()) >= 2) ++reach2_seen;
      const auto expect = brute_tilted<D>(s, box);
      ASSERT_FALSE(expect.empty());
      for (int L : {1, 2})
        for (int threads : {1, 2}) {
          const auto [got, c] = tilted_pairs<D, S>(s, box, exponential_sizes(L, 0.2, rmax), threads);
          ASSERT_EQ(std::adjacent_find(got.begin(), got.end()), got.end()) << "a pair was reported twice";
          ASSERT_EQ(got, expect) << "L = " << L << ", " << threads << " threads";
          ASSERT_EQ(c.contacts, expect.size());
        }
    }
  EXPECT_GT(narrow_seen, 0);
  EXPECT_GT(reach2_seen, 0);
}

TEST(HGridTilted, NarrowBoxesD2TopDown) { narrow_sweep<2, Search::top_down>(); }
TEST(HGridTilted, NarrowBoxesD2BottomUp) { narrow_sweep<2, Search::bottom_up>(); }
TEST(HGridTilted, NarrowBoxesD3TopDown) { narrow_sweep<3, Search::top_down>(); }
TEST(HGridTilted, NarrowBoxesD3BottomUp) { narrow_sweep<3, Search::bottom_up>(); }

}  // namespace
}  // namespace hgrid::test
