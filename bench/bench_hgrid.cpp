// Pair finding on random-centre packings: 3D, periodic, alpha = -3,
// omega = 100, nu = 0.6 (the pair-finding targets). HGrid with the model's optimal
// Top-Down sizes (a new grid per iteration, and one grid rebuilt in place)
// vs the single-level linked cell vs brute force.
//
//   build/bench_hgrid --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <vector>

#include "hgridlab/grid/brute_force.hpp"
#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/packing/generate.hpp"
#include "hgridlab/grid/hgrid.hpp"

namespace {

using namespace hgrid;
using Grid = HGrid<3, Boundary::periodic>;

constexpr double kAlpha = -3, kOmega = 100, kNu = 0.6;
constexpr std::uint64_t kSeed = 2014;

struct Fixture {
  std::vector<Sphere<3>> spheres;
  Extent<3> box;
  std::vector<double> optimal;  // model's optimal Top-Down sizes for this distribution
};

const Fixture& fixture(std::size_t n) {
  static std::map<std::size_t, std::unique_ptr<Fixture>> cache;
  auto& f = cache[n];
  if (!f) {
    f = std::make_unique<Fixture>();
    PackingSpec spec;
    spec.d = 3;
    spec.n = n;
    spec.nu = kNu;
    spec.alpha = kAlpha;
    spec.omega = kOmega;
    spec.boundary = Boundary::periodic;
    spec.placement = Placement::random;
    spec.seed = kSeed;
    spec.progress = false;
    const Packing p = generate_packing(spec);
    const PowerLaw dist(kAlpha, kOmega);
    f->spheres = p.spheres<3>();
    f->box = p.extent<3>();
    f->optimal = choose_cell_sizes(dist, ModelParams{3, kNu, 0.2, Search::top_down}, CellMethod::optimal).sizes;
  }
  return *f;
}

/// Wall time per particle per iteration, printed with SI prefixes (100n = 100 ns).
void set_per_particle(benchmark::State& state, double n) {
  state.counters["s_per_particle"] =
      benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <class Count>
void run_grid(benchmark::State& state, const std::vector<double>& sizes) {
  const auto& f = fixture(static_cast<std::size_t>(state.range(0)));
  std::uint64_t pairs = 0;
  std::size_t bytes = 0;
  for (auto _ : state) {
    const Grid grid(f.spheres, f.box, GridParams{sizes, Search::top_down});
    std::uint64_t found = 0;
    grid.query<Search::top_down, Count>([&found](std::uint32_t, std::uint32_t) { ++found; });
    benchmark::DoNotOptimize(found);
    pairs = found;
    bytes = grid.memory_bytes();
  }
  const double n = static_cast<double>(f.spheres.size());
  set_per_particle(state, n);
  state.counters["pairs_per_s"] = benchmark::Counter(static_cast<double>(pairs), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["pairs"] = static_cast<double>(pairs);
  state.counters["levels"] = static_cast<double>(sizes.size());
  state.counters["grid_bytes_per_particle"] = static_cast<double>(bytes) / n;
  state.counters["extra_bytes_per_particle"] = static_cast<double>(bytes) / n - sizeof(Sphere<3>);
}

void BM_HGridOptimal(benchmark::State& state) {
  run_grid<Uncounted>(state, fixture(static_cast<std::size_t>(state.range(0))).optimal);
}
void BM_HGridOptimalCounted(benchmark::State& state) {
  run_grid<Counted>(state, fixture(static_cast<std::size_t>(state.range(0))).optimal);
}
/// Construction alone (levels and cells, the two sorting steps, the
/// directory, the sweep order), to split the
/// build-plus-query time above into its two parts.
void BM_HGridBuild(benchmark::State& state) {
  const auto& f = fixture(static_cast<std::size_t>(state.range(0)));
  const int T = static_cast<int>(state.range(1));  // threads
  for (auto _ : state) {
    const Grid grid(f.spheres, f.box, GridParams{f.optimal, Search::top_down, T});
    benchmark::DoNotOptimize(grid.size());
  }
  set_per_particle(state, static_cast<double>(f.spheres.size()));
}
/// Rebuild plus query on one grid kept across iterations, as a code that
/// rebuilds every time step uses it: its arrays are reused.
void BM_HGridRebuild(benchmark::State& state) {
  const auto& f = fixture(static_cast<std::size_t>(state.range(0)));
  Grid grid(f.spheres, f.box, GridParams{f.optimal, Search::top_down});
  std::uint64_t pairs = 0;
  for (auto _ : state) {
    grid.rebuild(f.spheres);
    std::uint64_t found = 0;
    grid.query<Search::top_down>([&found](std::uint32_t, std::uint32_t) { ++found; });
    benchmark::DoNotOptimize(found);
    pairs = found;
  }
  const double n = static_cast<double>(f.spheres.size());
  set_per_particle(state, n);
  state.counters["pairs"] = static_cast<double>(pairs);
  state.counters["workspace_bytes_per_particle"] = static_cast<double>(grid.workspace_bytes()) / n;
}
/// Build plus query on T threads (the second argument; 0 = all cores), the
/// callback counting per thread (base/threads.hpp). Wall time: the ratio of
/// T = 1 to T = 2 at N = 10^6 in one run is the speed-up on two cores.
void BM_HGridThreads(benchmark::State& state) {
  const auto& f = fixture(static_cast<std::size_t>(state.range(0)));
  const int T = static_cast<int>(state.range(1));
  struct alignas(64) Slot {
    std::uint64_t n = 0;
  };
  std::vector<Slot> found(static_cast<std::size_t>(resolve_threads(T)));
  std::uint64_t pairs = 0;
  for (auto _ : state) {
    const Grid grid(f.spheres, f.box, GridParams{f.optimal, Search::top_down, T});
    for (auto& s : found) s.n = 0;
    grid.query<Search::top_down>([&found](int t, std::uint32_t, std::uint32_t) { ++found[t].n; });
    pairs = 0;
    for (const auto& s : found) pairs += s.n;
    benchmark::DoNotOptimize(pairs);
  }
  set_per_particle(state, static_cast<double>(f.spheres.size()));
  state.counters["pairs"] = static_cast<double>(pairs);
  state.counters["threads"] = resolve_threads(T);
}
void BM_LinkedCell(benchmark::State& state) { run_grid<Uncounted>(state, {2 * kOmega}); }

void BM_BruteForce(benchmark::State& state) {
  const auto& f = fixture(static_cast<std::size_t>(state.range(0)));
  std::uint64_t pairs = 0;
  for (auto _ : state) {
    std::uint64_t found = 0;
    brute_force_pairs<3, Boundary::periodic>(std::span<const Sphere<3>>(f.spheres), f.box,
                                             [&found](std::uint32_t, std::uint32_t) { ++found; });
    pairs = found;
  }
  set_per_particle(state, static_cast<double>(f.spheres.size()));
  state.counters["pairs"] = static_cast<double>(pairs);
}

BENCHMARK(BM_HGridOptimal)->Arg(10'000)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HGridOptimalCounted)->Arg(10'000)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HGridBuild)->Args({1'000'000, 1})->Args({1'000'000, 2})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HGridRebuild)->Arg(10'000)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond);
// One level of 2 r_max: O(N m) with m ~ hundreds of particles per cell; 10^6 takes minutes.
BENCHMARK(BM_HGridThreads)->Args({1'000'000, 1})->Args({1'000'000, 2})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LinkedCell)->Arg(10'000)->Arg(100'000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BruteForce)->Arg(10'000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
