// Contact detection step after step: the exact contact set of a moving
// polydisperse packing at every step, from an HGrid rebuilt and searched at
// every step (the baseline, the model's optimal sizes) against a ContactList
// with a skin (the same sizes). 3D, periodic, alpha = -3, omega = 5, nu =
// 0.4, excluded-volume placement; every particle moves ballistically by
// kStep r_min per step (a random direction each, fixed), outside the timing.
//   build/bench_contact_list --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <random>

#include "hgridlab/contacts/contact_list.hpp"
#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/packing/generate.hpp"

using namespace hgrid;

namespace {

constexpr std::uint64_t kSeed = 7;
constexpr double kNu = 0.4, kAlpha = -3, kOmega = 5;
/// Displacement per step, in units of r_min (a DEM step moves a particle
/// by a small fraction of its radius).
constexpr double kStep = 0.01;

struct Moving {
  Packing p;
  std::vector<Sphere<3>> s;
  std::vector<std::array<double, 3>> v;
  Extent<3> box;
  void step() {
    for (std::size_t i = 0; i < s.size(); ++i)
      for (int k = 0; k < 3; ++k) s[i].x[k] = detail::wrap(s[i].x[k] + v[i][k], box[k]);
  }
};

Moving generate_moving(std::size_t n) {
  Moving m;
  m.p = generate_packing({.d = 3, .n = n, .nu = kNu, .alpha = kAlpha, .omega = kOmega, .boundary = Boundary::periodic,
                          .placement = Placement::excluded, .seed = kSeed, .progress = false});
  m.s = m.p.spheres<3>();
  for (int k = 0; k < 3; ++k) m.box[k] = m.p.box[k];
  std::mt19937_64 rng(kSeed);
  std::normal_distribution<double> g(0.0, 1.0);
  m.v.resize(n);
  for (auto& v : m.v) {
    double norm = 0;
    for (auto& c : v) {
      c = g(rng);
      norm += c * c;
    }
    for (auto& c : v) c *= kStep / std::sqrt(norm);
  }
  return m;
}

/// A fresh copy of the packing of n particles (generated once per n).
Moving make_moving(std::size_t n) {
  static std::map<std::size_t, Moving> made;
  auto it = made.find(n);
  if (it == made.end()) it = made.emplace(n, generate_moving(n)).first;
  return it->second;
}

const std::vector<double>& optimal_sizes() {
  static const std::vector<double> s =
      choose_cell_sizes(PowerLaw(kAlpha, kOmega), ModelParams{3, kNu, 0.2, Search::top_down}, CellMethod::optimal).sizes;
  return s;
}

// range(0): N. The HGrid rebuilt and searched at every step, its pairs collected.
void BM_RebuildEveryStep(benchmark::State& st) {
  Moving m = make_moving(static_cast<std::size_t>(st.range(0)));
  HGrid<3, Boundary::periodic> grid(m.s, m.box, GridParams{optimal_sizes(), Search::top_down, 1});
  std::vector<std::uint64_t> keys;
  std::uint64_t contacts = 0;
  for (auto _ : st) {
    st.PauseTiming();
    m.step();
    st.ResumeTiming();
    grid.rebuild(m.s);
    keys.clear();
    grid.for_each_pair([&](std::uint32_t i, std::uint32_t j) { keys.push_back((std::uint64_t{i} << 32) | j); });
    contacts += keys.size();
  }
  st.counters["contacts_per_n"] = double(contacts) / double(st.iterations()) / double(m.s.size());
  st.SetItemsProcessed(st.iterations() * st.range(0));
}
BENCHMARK(BM_RebuildEveryStep)->Arg(10000)->Arg(100000)->Iterations(200)->Unit(benchmark::kMillisecond);

// range(0): N; range(1): the pair skin in thousandths of r_min. The list is
// made and filled before the timing (its first build). A fixed number of
// steps, so that every run (and every binary) times the same states.
void BM_ContactListStep(benchmark::State& st) {
  Moving m = make_moving(static_cast<std::size_t>(st.range(0)));
  ContactList<3> list(ListBox<3>{m.box, {}, {true, true, true}},
                      ContactListParams{optimal_sizes(), Search::top_down, 1, double(st.range(1)) / 1000, 0.0});
  list.update(m.s);
  const std::uint64_t builds0 = list.stats().builds;
  const ContactListStats s0 = list.stats();
  std::uint64_t contacts = 0, candidates = 0;
  for (auto _ : st) {
    st.PauseTiming();
    m.step();
    st.ResumeTiming();
    list.update(m.s);
    contacts += list.contacts();
    candidates += list.candidates();
  }
  const double it = double(st.iterations()), n = double(m.s.size());
  st.counters["contacts_per_n"] = double(contacts) / it / n;
  st.counters["candidates_per_n"] = double(candidates) / it / n;
  st.counters["steps_per_build"] = it / std::max(1.0, double(list.stats().builds - builds0));
  const ContactListStats& s1 = list.stats();  // where a step's time goes, ms per step
  st.counters["check_ms"] = 1e3 * (s1.seconds_check - s0.seconds_check) / it;
  st.counters["build_ms"] = 1e3 * (s1.seconds_build - s0.seconds_build) / it;
  st.counters["test_ms"] = 1e3 * (s1.seconds_test - s0.seconds_test) / it;
  st.SetItemsProcessed(st.iterations() * st.range(0));
}
BENCHMARK(BM_ContactListStep)
    ->ArgsProduct({{10000, 100000}, {0, 50, 100, 200, 400, 800}})
    ->Iterations(200)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
