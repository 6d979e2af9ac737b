// Packing generation at the paper's scale (the generators' targets), 3D periodic:
//   random placement, N = 1e6                         (target <= 1 s)
//   excluded volume, alpha = -3, omega = 100, nu = 0.6 (target <= 2 min, zero overlap)
//   excluded volume, alpha = 0, omega = 10, nu = 0.6   (target <= 15 min, max rel. overlap <= 1e-4)
//   hard-sphere Monte Carlo with swaps, N = 1e5: sweeps/s and moves/s per thread,
//   Metropolis moves (overlap tests on move lists, and on the grid alone) and
//   event chains in one run
// Run one at a time (the peak-memory counter is per process):
//   build/bench_generate --benchmark_filter='Rsa/1000000/'
#include <benchmark/benchmark.h>

#include <fstream>
#include <string>

#include "hgridlab/packing/generate.hpp"

namespace {

using namespace hgrid;

constexpr std::uint64_t kSeed = 2014;

/// Peak resident memory of this process (VmHWM), bytes.
double peak_rss_bytes() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) * 1024.0;
  return 0;
}

void run(benchmark::State& state, double alpha, double omega, Placement placement) {
  PackingSpec s;
  s.d = 3;
  s.n = static_cast<std::size_t>(state.range(0));
  s.nu = 0.6;
  s.alpha = alpha;
  s.omega = omega;
  s.placement = placement;
  s.seed = kSeed;
  s.progress = false;
  Packing p;
  for (auto _ : state) p = generate_packing(s);
  const PackingQuality q = assess_packing(p, make_distribution(s).get(), placement == Placement::excluded);
  state.counters["nu"] = q.nu;
  state.counters["max_rel_overlap"] = q.max_rel_overlap;
  state.counters["mean_rel_overlap"] = q.mean_rel_overlap;
  state.counters["slab_dev"] = q.slab_max_dev;
  for (std::size_t b = 0; b < q.band_slab_max_dev.size(); ++b)
    state.counters["band" + std::to_string(b) + "_slab_dev"] = q.band_slab_max_dev[b];
  state.counters["ks_p"] = q.ks_pvalue;
  state.counters["fire_steps"] = p.num_attrs.count("fire_steps") ? p.num_attrs.at("fire_steps") : 0.0;
  state.counters["peak_bytes_per_particle"] = peak_rss_bytes() / static_cast<double>(s.n);
}

/// The hard-sphere Monte Carlo with swaps that equilibrates the packings of
/// Figs. 11-12 (packing/detail/gen_equilibrate.cpp), from the placed packing
/// (generated before the timing): N = 10^5, nu = 0.6, alpha = -3, omega =
/// range(0), on range(1) threads; Metropolis moves or event chains (one
/// thread; gen_event_chain.hpp). Counters: sweeps per second and particle
/// moves (Metropolis trials, or chain events) per second and thread. One run
/// of the binary times both kinds (an A/B of the two move kinds); what a sweep of each
/// buys is in docs/MODEL.md section 8 (event chains relax the large
/// particles in tens of sweeps where Metropolis moves take thousands).
void monte_carlo(benchmark::State& state, EquilibrationMoves moves, OverlapSearch search = OverlapSearch::lists) {
  constexpr int kSweeps = 20;
  PackingSpec s;
  s.d = 3;
  s.n = 100000;
  s.nu = 0.6;
  s.alpha = -3;
  s.omega = static_cast<double>(state.range(0));
  s.placement = Placement::excluded;
  s.seed = kSeed;
  s.progress = false;
  const Packing placed = generate_packing(s);
  PackingSpec e = s;
  e.equilibrate = true;
  e.sweeps = kSweeps;
  e.moves = moves;
  e.threads = static_cast<int>(state.range(1));
  e.overlap_search = search;
  for (auto _ : state) {
    Packing p = generate_packing(e, &placed);
    benchmark::DoNotOptimize(p.radii.data());
  }
  const double sweeps = static_cast<double>(kSweeps) * static_cast<double>(state.iterations());
  const double threads = moves == EquilibrationMoves::event_chain ? 1.0 : static_cast<double>(e.threads);
  state.counters["sweeps_per_s"] = benchmark::Counter(sweeps, benchmark::Counter::kIsRate);
  state.counters["moves_per_s_per_thread"] =
      benchmark::Counter(sweeps * static_cast<double>(s.n) / threads, benchmark::Counter::kIsRate);
}

void BM_MonteCarlo(benchmark::State& state) { monte_carlo(state, EquilibrationMoves::metropolis); }
/// The same Metropolis sweeps with every overlap test on the insertion grid
/// (the test the move lists replaced; the same packing): the A/B in one run.
void BM_MonteCarloGridTests(benchmark::State& state) {
  monte_carlo(state, EquilibrationMoves::metropolis, OverlapSearch::grid);
}
void BM_EventChain(benchmark::State& state) { monte_carlo(state, EquilibrationMoves::event_chain); }

void BM_Random(benchmark::State& state) { run(state, -3, 100, Placement::random); }
void BM_Rsa(benchmark::State& state) { run(state, -3, 100, Placement::excluded); }
void BM_Growth(benchmark::State& state) { run(state, 0, 10, Placement::excluded); }

BENCHMARK(BM_Random)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_Rsa)->Arg(100000)->Arg(1000000)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_MonteCarlo)->Args({10, 1})->Args({10, 2})->Args({100, 1})->Args({100, 2})->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_MonteCarloGridTests)->Args({10, 1})->Args({10, 2})->Args({100, 1})->Args({100, 2})->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_EventChain)->Args({10, 1})->Args({100, 1})->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Growth)->Arg(100000)->Arg(1000000)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
