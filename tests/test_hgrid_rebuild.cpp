// HGrid::rebuild: one grid rebuilt over a sequence of moving, growing and
// shrinking packings gives exactly what a freshly constructed grid gives
// (pair sets against brute force, and every count), reuses its memory, and
// leaves itself unchanged when an input is rejected.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <limits>
#include <new>

#include "hgridlab/base/error.hpp"
#include "support.hpp"

// Every allocation of this test program through operator new is counted, so
// that a test can check that a rebuild allocates nothing. libstdc++'s other
// forms (nothrow, aligned) end in these or in malloc / free; under
// AddressSanitizer, which brings its own forms of all of them, the count is
// left out (replacing only these would mix its allocator with free).
// GCC says AddressSanitizer by __SANITIZE_ADDRESS__, clang by __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define HGRID_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HGRID_TEST_ASAN 1
#endif
#endif
namespace {
std::atomic<std::size_t> g_allocations{0};
#if defined(HGRID_TEST_ASAN)
constexpr bool kCountsAllocations = false;
#else
constexpr bool kCountsAllocations = true;
#endif
}  // namespace
namespace hgrid::test {
std::size_t allocations() { return g_allocations.load(); }
bool counts_allocations() { return kCountsAllocations; }
}  // namespace hgrid::test
#if !defined(HGRID_TEST_ASAN)
// GCC flags free() on a pointer from operator new once it inlines both;
// here both sides are malloc/free, so the pair matches.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return ::operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop
#endif

namespace hgrid::test {
namespace {

/// The first n particles of s, each moved by up to `step` per axis (walls:
/// kept inside the box), as a time-stepping code would hand them over.
template <int D>
Scene<D> moved(const Scene<D>& s, std::size_t n, double step, Boundary b, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-step, step);
  Scene<D> out{{s.spheres.begin(), s.spheres.begin() + static_cast<std::ptrdiff_t>(n)}, s.box};
  for (auto& p : out.spheres)
    for (int a = 0; a < D; ++a) {
      p.x[a] += u(rng);
      if (b == Boundary::walls) p.x[a] = std::clamp(p.x[a], 0.0, s.box[a]);
    }
  return out;
}


template <int D, Boundary B>
void check_sequence(std::uint64_t seed) {
  const Scene<D> base = random_scene<D>(3000, 0.4, -3.0, 20.0, B, seed);
  const std::vector<double> sizes = exponential_sizes(4, 1.0, 20.0);
  HGrid<D, B> grid(std::span<const Sphere<D>>(base.spheres), base.box, GridParams{sizes, Search::top_down});
  EXPECT_EQ(grid.workspace_bytes(), 0u);
  // Grow, move, shrink to one and to none, grow again.
  const std::size_t counts[] = {3000, 3000, 1200, 1, 0, 2500, 3000};
  for (std::size_t k = 0; k < std::size(counts); ++k) {
    const std::uint64_t step_seed = seed * 100 + k;
    SCOPED_TRACE("seed " + std::to_string(seed) + ", step " + std::to_string(k) + ", n = " + std::to_string(counts[k]));
    const Scene<D> s = moved(base, counts[k], 0.7, B, step_seed);
    grid.rebuild(std::span<const Sphere<D>>(s.spheres));
    const HGrid<D, B> fresh(std::span<const Sphere<D>>(s.spheres), s.box, GridParams{sizes, Search::top_down});
    const auto expect = brute_pairs<D, B>(s);
    const auto td = query_pairs<Search::top_down, Counted>(grid);
    EXPECT_EQ(td.first, expect);
    expect_same_counters(td.second, query_pairs<Search::top_down, Counted>(fresh).second);
    const auto bu = query_pairs<Search::bottom_up, Counted>(grid);
    EXPECT_EQ(bu.first, expect);
    expect_same_counters(bu.second, query_pairs<Search::bottom_up, Counted>(fresh).second);
    EXPECT_EQ(grid.size(), s.spheres.size());
    EXPECT_EQ(grid.particles_per_level(), fresh.particles_per_level());
  }
}

TEST(HGridRebuild, SameAsFreshGrid3DPeriodic) {
  for (std::uint64_t seed : {1, 2}) check_sequence<3, Boundary::periodic>(seed);
}
TEST(HGridRebuild, SameAsFreshGrid3DWalls) {
  for (std::uint64_t seed : {3, 4}) check_sequence<3, Boundary::walls>(seed);
}
TEST(HGridRebuild, SameAsFreshGrid2DPeriodic) { check_sequence<2, Boundary::periodic>(5); }
TEST(HGridRebuild, SameAsFreshGrid2DWalls) { check_sequence<2, Boundary::walls>(6); }

// Rebuilt in a new box (compressed, then expanded past the start): the same
// pairs and counts as a fresh grid in that box; a rejected box (a side of 0,
// or cells too small for it) leaves the grid as it was, box included.
template <int D, Boundary B>
void check_new_boxes(std::uint64_t seed) {
  const Scene<D> base = random_scene<D>(2000, 0.3, -3.0, 8.0, B, seed);
  const std::vector<double> sizes = exponential_sizes(3, 1.0, 8.0);
  HGrid<D, B> grid(std::span<const Sphere<D>>(base.spheres), base.box, GridParams{sizes, Search::top_down});
  for (const double f : {0.97, 0.9, 1.05}) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", box x " + std::to_string(f));
    Scene<D> s = base;
    for (int a = 0; a < D; ++a) s.box[a] *= f;
    for (auto& p : s.spheres)
      for (int a = 0; a < D; ++a) p.x[a] *= f;
    grid.rebuild(std::span<const Sphere<D>>(s.spheres), s.box);
    const HGrid<D, B> fresh(std::span<const Sphere<D>>(s.spheres), s.box, GridParams{sizes, Search::top_down});
    const auto got = query_pairs<Search::top_down, Counted>(grid);
    EXPECT_EQ(got.first, (brute_pairs<D, B>(s)));
    expect_same_counters(got.second, query_pairs<Search::top_down, Counted>(fresh).second);
    EXPECT_EQ(grid.box(), s.box);
    EXPECT_EQ(grid.sizes(), fresh.sizes());
    // Rejected boxes change nothing.
    Extent<D> flat = s.box;
    flat[0] = 0;
    EXPECT_THROW(grid.rebuild(std::span<const Sphere<D>>(s.spheres), flat), InputError);
    Extent<D> huge = s.box;
    huge[D - 1] = 1e7;
    EXPECT_THROW(grid.rebuild(std::span<const Sphere<D>>(s.spheres), huge), InputError);
    EXPECT_EQ(grid.box(), s.box);
    EXPECT_EQ((query_pairs<Search::top_down, Counted>(grid).first), got.first);
  }
}
TEST(HGridRebuild, InANewBoxSameAsFreshGrid) {
  check_new_boxes<3, Boundary::periodic>(21);
  check_new_boxes<3, Boundary::walls>(22);
  check_new_boxes<2, Boundary::periodic>(23);
  check_new_boxes<2, Boundary::walls>(24);
}

// A level that is ranked in one build and hashed in the next (its particle
// count changes the directory's layout: its ~134 000 cells of side 2 are
// ranked for 4000 particles, hashed for 3), and back.
TEST(HGridRebuild, DirectoryLayoutChangesBetweenBuilds) {
  const Scene<3> dense = random_scene<3>(4000, 0.02, 0.0, 1.0, Boundary::periodic, 7);
  const Scene<3> sparse = moved(dense, 3, 0.5, Boundary::periodic, 8);
  const std::vector<double> sizes{2.0, 2.5};
  HGrid<3, Boundary::periodic> grid(std::span<const Sphere<3>>(dense.spheres), dense.box, GridParams{sizes});
  for (const Scene<3>* s : {&sparse, &dense, &sparse}) {
    grid.rebuild(std::span<const Sphere<3>>(s->spheres));
    EXPECT_EQ((query_pairs<Search::top_down, Counted>(grid).first), (brute_pairs<3, Boundary::periodic>(*s)));
  }
}

// On one thread and on several (the per-thread workspace is kept too).
void check_reuse(int threads) {
  SCOPED_TRACE("threads = " + std::to_string(threads));
  const Scene<3> s = random_scene<3>(20000, 0.5, -3.0, 10.0, Boundary::periodic, 9);
  HGrid<3, Boundary::periodic> grid(std::span<const Sphere<3>>(s.spheres), s.box,
                                    GridParams{exponential_sizes(3, 1.0, 10.0), Search::top_down, threads});
  grid.rebuild(std::span<const Sphere<3>>(s.spheres));
  const std::size_t mem = grid.memory_bytes(), ws = grid.workspace_bytes();
  EXPECT_GT(ws, 20u * s.spheres.size());  // at least the keys and coarse buckets
  for (std::uint64_t k = 0; k < 3; ++k) {
    const Scene<3> m = moved(s, s.spheres.size(), 0.3, Boundary::periodic, 10 + k);
    grid.rebuild(std::span<const Sphere<3>>(m.spheres));
    EXPECT_EQ(grid.memory_bytes(), mem);
    EXPECT_EQ(grid.workspace_bytes(), ws);
  }
  // The same particles again: every array already has its size, so the
  // rebuild allocates nothing.
  const Scene<3> last = moved(s, s.spheres.size(), 0.3, Boundary::periodic, 12);
  grid.rebuild(std::span<const Sphere<3>>(last.spheres));
  const std::size_t before = g_allocations.load();
  grid.rebuild(std::span<const Sphere<3>>(last.spheres));
  if (kCountsAllocations) {
    EXPECT_EQ(g_allocations.load() - before, 0u);
  }
  // The workspace is not part of the grid's value: a copy has none, and
  // finds the same pairs.
  const std::size_t before_copy = g_allocations.load();
  const auto copy = grid;
  if (kCountsAllocations) {
    EXPECT_GT(g_allocations.load() - before_copy, 0u);  // the count does see the grid's arrays
  }
  EXPECT_EQ(copy.workspace_bytes(), 0u);
  EXPECT_EQ((query_pairs<Search::top_down, Counted>(copy).first),
            (query_pairs<Search::top_down, Counted>(grid).first));
}

TEST(HGridRebuild, ReusesItsMemory) { check_reuse(1); }
TEST(HGridRebuild, ReusesItsMemoryOnTwoThreads) { check_reuse(2); }

TEST(HGridRebuild, RejectedInputLeavesGridUnchanged) {
  const Scene<3> s = random_scene<3>(2000, 0.4, -3.0, 10.0, Boundary::walls, 11);
  const std::vector<double> sizes = exponential_sizes(3, 1.0, 10.0);
  HGrid<3, Boundary::walls> grid(std::span<const Sphere<3>>(s.spheres), s.box, GridParams{sizes});
  const auto before = query_pairs<Search::top_down, Counted>(grid).first;
  ASSERT_FALSE(before.empty());
  auto bad = s.spheres;
  bad[1500].x[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(grid.rebuild(std::span<const Sphere<3>>(bad)), InputError);
  bad = s.spheres;
  bad[10].r = 2 * sizes.back();  // larger than the largest cell
  EXPECT_THROW(grid.rebuild(std::span<const Sphere<3>>(bad)), InputError);
  bad = s.spheres;
  bad[1999].x[0] = -1.0;  // outside the walled box
  EXPECT_THROW(grid.rebuild(std::span<const Sphere<3>>(bad)), InputError);
  EXPECT_EQ(grid.size(), s.spheres.size());
  EXPECT_EQ((query_pairs<Search::top_down, Counted>(grid).first), before);
}

}  // namespace
}  // namespace hgrid::test
