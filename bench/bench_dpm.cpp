// DPM step cost: a switched-off effect costs nothing (friction / gravity
// compiled out), and the optimal HGrid vs the linked cell on the paper's
// free-cooling distribution (2D, walls, alpha = -3, omega = 20, nu = 0.4).
#include <benchmark/benchmark.h>

#include <random>

#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/dpm/simulation.hpp"
#include "hgridlab/packing/generate.hpp"

using namespace hgrid;

namespace {

constexpr std::uint64_t kSeed = 7;

// A packing generated once (seed kSeed, no progress lines).
Packing make_packing(int d, std::size_t n, double nu, double alpha, double omega, Boundary b, Placement placement) {
  return generate_packing({.d = d, .n = n, .nu = nu, .alpha = alpha, .omega = omega, .boundary = b,
                           .placement = placement, .seed = kSeed, .progress = false});
}

const Packing& initial() {  // excluded volume: a DEM state has no large overlaps
  static const Packing p = make_packing(2, 10000, 0.4, -3, 20, Boundary::walls, Placement::excluded);
  return p;
}

std::vector<double> velocities(std::size_t n) {
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> v(n);
  for (auto& x : v) x = g(rng);
  return v;
}

// range(0): 0 = plain, 1 = friction, 2 = friction + gravity; range(1): 0 = optimal, 1 = linked cell.
void BM_DpmStep(benchmark::State& st) {
  const Packing& p = initial();
  dpm::DpmConfig c;
  c.d = 2;
  c.boundary = Boundary::walls;
  c.box = p.box;
  c.contact_time = 0.05;
  c.dt = 0.0025;
  c.friction = st.range(0) >= 1;
  c.gravity = st.range(0) == 2;
  c.g = {0, -0.01, 0};
  c.sizes = st.range(1) == 0 ? choose_cell_sizes(PowerLaw(-3, 20), ModelParams{2, 0.4, 0.2, Search::top_down},
                                                 CellMethod::optimal)
                                   .sizes
                             : std::vector<double>{40.0};
  auto sim = dpm::make_simulation(c, p, velocities(p.size() * 2));
  for (auto _ : st) sim->run(1);
  st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(p.size()));
  st.SetLabel(std::string(st.range(0) == 0 ? "plain" : st.range(0) == 1 ? "friction" : "friction+gravity") +
              (st.range(1) == 0 ? ", optimal" : ", linked cell"));
}
BENCHMARK(BM_DpmStep)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond);

// A dense contact network (3D, periodic, N = 10^5, alpha = -3, omega = 10,
// random centres at nu = 0.5: ~2.6 contacts per particle, as in a packed bed),
// with friction, on range(0) threads: the step's parts are reported as
// counters (ms per step), so that the share of contact detection, forces and
// integration can be read.
const Packing& dense() {
  static const Packing p = make_packing(3, 100000, 0.5, -3, 10, Boundary::periodic, Placement::random);
  return p;
}

void BM_DpmDenseStep(benchmark::State& st) {
  const Packing& p = dense();
  dpm::DpmConfig c;
  c.d = 3;
  c.boundary = Boundary::periodic;
  c.box = p.box;
  c.contact_time = 1.0;  // soft and slow: the overlaps stay for the run
  c.dt = 0.05;
  c.friction = true;
  c.threads = static_cast<int>(st.range(0));
  c.sizes = choose_cell_sizes(PowerLaw(-3, 10), ModelParams{3, 0.5, 0.2, Search::top_down}, CellMethod::optimal).sizes;
  auto sim = dpm::make_simulation(c, p, std::vector<double>(p.size() * 3, 0.0));
  for (auto _ : st) sim->run(1);
  const auto& s = sim->stats();
  const double steps = static_cast<double>(s.steps);
  st.counters["contacts_per_particle"] = static_cast<double>(s.pair_contacts) / steps / static_cast<double>(p.size());
  st.counters["ms_detect"] = 1e3 * s.seconds_contact_detection / steps;
  st.counters["ms_forces"] = 1e3 * s.seconds_forces / steps;
  st.counters["ms_integrate"] = 1e3 * s.seconds_integration / steps;
  st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(p.size()));
}
BENCHMARK(BM_DpmDenseStep)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
BENCHMARK_MAIN();
