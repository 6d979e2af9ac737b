// The grid on several threads (base/threads.hpp): for 1, 2, 3 and 8 threads
// (8 oversubscribed on a 2-core machine) the same pair SET as an O(N^2)
// brute force, and counters identical to one thread's, for the build and the
// query, both search directions, walls and periodic, 2D and 3D; the
// thread-index callback; concurrent queries of one const grid; errors. The
// counts alone (CountsOnly) equal Counted's but the contacts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "support.hpp"

namespace {

using namespace hgrid;
using namespace hgrid::test;

constexpr int kThreadCounts[] = {1, 2, 3, 8};


/// The pairs (sorted, duplicates kept) and counters of a grid built and
/// queried on `threads` threads; the callback locks (the f(i, j) contract).
template <int D, Boundary B, Search S>
std::pair<std::vector<Pair>, Counters> on_threads(const Scene<D>& s, const std::vector<double>& sizes, int threads) {
  const HGrid<D, B> grid(std::span<const Sphere<D>>(s.spheres), s.box, GridParams{sizes, S, threads});
  std::vector<Pair> out;
  std::mutex m;
  const Counters c = grid.template query<S, Counted>([&](std::uint32_t i, std::uint32_t j) {
    const std::lock_guard<std::mutex> lock(m);
    out.emplace_back(i, j);
  });
  std::sort(out.begin(), out.end());
  return {out, c};
}

template <int D, Boundary B>
void check_scene(const Scene<D>& s, const std::vector<double>& sizes) {
  const auto expect = brute_pairs<D, B>(s);
  for (const Search S : {Search::top_down, Search::bottom_up}) {
    SCOPED_TRACE(to_string(S));
    const auto one = S == Search::top_down ? on_threads<D, B, Search::top_down>(s, sizes, 1)
                                           : on_threads<D, B, Search::bottom_up>(s, sizes, 1);
    EXPECT_EQ(one.first, expect);
    for (const int t : kThreadCounts) {
      SCOPED_TRACE("threads = " + std::to_string(t));
      const auto r = S == Search::top_down ? on_threads<D, B, Search::top_down>(s, sizes, t)
                                           : on_threads<D, B, Search::bottom_up>(s, sizes, t);
      EXPECT_EQ(r.first, expect);
      expect_same_counters(r.second, one.second);
      // The counts alone: every counter the same but the contacts (none
      // tested), and the callback never called.
      const HGrid<D, B> grid(std::span<const Sphere<D>>(s.spheres), s.box, GridParams{sizes, S, t});
      std::uint64_t calls = 0;
      Counters only = grid.template for_each_pair<CountsOnly>([&](std::uint32_t, std::uint32_t) { ++calls; });
      EXPECT_EQ(calls, 0u);
      EXPECT_EQ(only.contacts, 0u);
      only.contacts = one.second.contacts;
      expect_same_counters(only, one.second);
    }
  }
}

// Seeds 1-8, printed by SCOPED_TRACE; N large enough that a build of 8
// threads uses all of them (at least HGrid::kMinParticlesPerThread each).
TEST(HGridThreads, SameAsBruteForce3DPeriodic) {
  const Scene<3> s = random_scene<3>(12000, 0.4, -3.0, 20.0, Boundary::periodic, 1);
  SCOPED_TRACE("seed 1");
  check_scene<3, Boundary::periodic>(s, exponential_sizes(4, 1.0, 20.0));
}
TEST(HGridThreads, SameAsBruteForce3DWalls) {
  const Scene<3> s = random_scene<3>(12000, 0.3, -2.0, 10.0, Boundary::walls, 2);
  SCOPED_TRACE("seed 2");
  check_scene<3, Boundary::walls>(s, exponential_sizes(3, 1.0, 10.0));
}
TEST(HGridThreads, SameAsBruteForce2DPeriodic) {
  const Scene<2> s = random_scene<2>(12000, 0.5, -3.0, 50.0, Boundary::periodic, 3);
  SCOPED_TRACE("seed 3");
  check_scene<2, Boundary::periodic>(s, exponential_sizes(5, 1.0, 50.0));
}
TEST(HGridThreads, SameAsBruteForce2DWalls) {
  const Scene<2> s = random_scene<2>(12000, 0.2, -3.0, 5.0, Boundary::walls, 4);
  SCOPED_TRACE("seed 4");
  check_scene<2, Boundary::walls>(s, exponential_sizes(2, 1.0, 5.0));
}
// Hashed levels (many more cells than particles: tiny lowest cells for a
// few small particles) next to ranked ones, and a single level.
TEST(HGridThreads, SameAsBruteForceHashedLevels) {
  Scene<3> s = random_scene<3>(10000, 0.3, 0.0, 1.0, Boundary::periodic, 5);
  for (std::size_t i = 0; i < 40; ++i) s.spheres[i * 50].r = 0.01;
  SCOPED_TRACE("seed 5");
  check_scene<3, Boundary::periodic>(s, {0.02, 0.5, 2.0});
  check_scene<3, Boundary::periodic>(s, {2.0});
}

TEST(HGridThreads, ThreadIndexCallback) {
  const Scene<3> s = random_scene<3>(12000, 0.5, -3.0, 10.0, Boundary::periodic, 6);
  const std::vector<double> sizes = exponential_sizes(3, 1.0, 10.0);
  const HGrid<3, Boundary::periodic> grid(std::span<const Sphere<3>>(s.spheres), s.box, GridParams{sizes});
  const auto expect = brute_pairs<3, Boundary::periodic>(s);
  for (const int T : kThreadCounts) {
    std::vector<std::vector<Pair>> per(T);  // no lock: thread t writes only per[t]
    grid.query<Search::top_down>([&](int t, std::uint32_t i, std::uint32_t j) { per.at(t).emplace_back(i, j); }, T);
    std::vector<Pair> all;
    for (const auto& v : per) all.insert(all.end(), v.begin(), v.end());
    std::sort(all.begin(), all.end());
    EXPECT_EQ(all, expect) << "threads = " << T;
  }
}

// A const grid queried from four threads at once, each query itself on 2.
TEST(HGridThreads, ConcurrentQueriesOfAConstGrid) {
  const Scene<3> s = random_scene<3>(10000, 0.4, -3.0, 10.0, Boundary::walls, 7);
  const HGrid<3, Boundary::walls> grid(std::span<const Sphere<3>>(s.spheres), s.box,
                                       GridParams{exponential_sizes(3, 1.0, 10.0), Search::top_down, 2});
  const auto expect = query_pairs<Search::top_down, Counted>(grid);
  std::vector<std::pair<std::vector<Pair>, Counters>> got(4);
  std::vector<std::thread> workers;
  for (auto& g : got) workers.emplace_back([&] { g = query_pairs<Search::top_down, Counted>(grid); });
  for (auto& w : workers) w.join();
  for (const auto& g : got) {
    EXPECT_EQ(g.first, expect.first);
    expect_same_counters(g.second, expect.second);
  }
}

TEST(HGridThreads, CallbackExceptionReachesTheCaller) {
  const Scene<3> s = random_scene<3>(12000, 0.5, -3.0, 10.0, Boundary::periodic, 8);
  const HGrid<3, Boundary::periodic> grid(std::span<const Sphere<3>>(s.spheres), s.box,
                                          GridParams{exponential_sizes(3, 1.0, 10.0), Search::top_down, 3});
  EXPECT_THROW(grid.query<Search::bottom_up>([](std::uint32_t, std::uint32_t) { throw std::runtime_error("stop"); }),
               std::runtime_error);
}

// The error of a bad input names the lowest bad index, whatever the threads.
TEST(HGridThreads, InputErrorNamesTheFirstBadParticle) {
  Scene<3> s = random_scene<3>(12000, 0.5, -3.0, 10.0, Boundary::walls, 9);
  s.spheres[9000].r = -1;
  s.spheres[7000].x[1] = -5;
  for (const int t : kThreadCounts) {
    try {
      const HGrid<3, Boundary::walls> g(std::span<const Sphere<3>>(s.spheres), s.box,
                                        GridParams{exponential_sizes(3, 1.0, 10.0), Search::top_down, t});
      ADD_FAILURE() << "accepted, threads = " << t;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("particle 7000"), std::string::npos) << e.what();
    }
  }
}

TEST(HGridThreads, ResolveThreads) {
  EXPECT_EQ(resolve_threads(1), 1);
  EXPECT_GE(resolve_threads(0), 1);
  if (kHaveThreads) {
    EXPECT_EQ(resolve_threads(3), 3);
  }
}

}  // namespace

namespace {

// The pieces of a query's decomposition cover its work exactly once: their
// counts add up to one query's, for any number of threads simulated.
TEST(HGridThreads, PiecesAddUpToTheQuery) {
  const Scene<3> s = random_scene<3>(12000, 0.5, -3.0, 50.0, Boundary::periodic, 10);
  const HGrid<3, Boundary::periodic> grid(std::span<const Sphere<3>>(s.spheres), s.box,
                                          GridParams{exponential_sizes(5, 1.0, 50.0)});
  for (const Search S : {Search::top_down, Search::bottom_up}) {
    const Counters whole = S == Search::top_down ? query_pairs<Search::top_down, Counted>(grid).second
                                                 : query_pairs<Search::bottom_up, Counted>(grid).second;
    for (const int P : {1, 2, 8, 64, 256}) {
      SCOPED_TRACE(std::string(to_string(S)) + ", P = " + std::to_string(P));
      const auto pieces = S == Search::top_down ? grid.counted_pieces<Search::top_down>(P)
                                                : grid.counted_pieces<Search::bottom_up>(P);
      Counters sum;
      std::uint64_t particles = 0;
      for (const auto& p : pieces) {
        sum.add(p.counts);
        particles += p.particles;
      }
      EXPECT_EQ(sum.cell_accesses, whole.cell_accesses);
      EXPECT_EQ(sum.narrow_phase_checks, whole.narrow_phase_checks);
      EXPECT_EQ(sum.contacts, whole.contacts);
      EXPECT_EQ(sum.searches, whole.searches);
      EXPECT_EQ(sum.rows, whole.rows);
      EXPECT_EQ(sum.occupied_cells, whole.occupied_cells);
      EXPECT_EQ(particles, s.spheres.size());
      if (P > 1) {
        EXPECT_GE(pieces.size(), static_cast<std::size_t>(std::min(P, 16)));
      }
    }
  }
}

}  // namespace
