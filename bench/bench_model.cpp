// Cost-model timings: optimal sizes for one (alpha, omega, L)
// <= 5 ms; L* search <= 50 ms. Figure data: time `hgrid modelfigs`.
#include <benchmark/benchmark.h>

#include "hgridlab/model/cell_sizes.hpp"

using namespace hgrid;

static void BM_OptimalSizesFixedL(benchmark::State& st) {
  const PowerLaw f(-3.0, static_cast<double>(st.range(0)));
  const int L = static_cast<int>(st.range(1));
  for (auto _ : st) benchmark::DoNotOptimize(cell_sizes(f, ModelParams{}, CellMethod::optimal, L));
}
BENCHMARK(BM_OptimalSizesFixedL)->Args({100, 4})->Args({100, 9})->Args({1000, 9})->Unit(benchmark::kMillisecond);

static void BM_BestLevels(benchmark::State& st) {
  const PowerLaw f(-3.0, static_cast<double>(st.range(0)));
  const auto m = static_cast<CellMethod>(st.range(1));
  for (auto _ : st) benchmark::DoNotOptimize(choose_cell_sizes(f, ModelParams{}, m));
  st.SetLabel(to_string(m));
}
BENCHMARK(BM_BestLevels)
    ->ArgsProduct({{100, 1000}, {0, 1, 2, 3}})
    ->Unit(benchmark::kMillisecond);

static void BM_EvaluateModel(benchmark::State& st) {
  const PowerLaw f(-3.0, 100.0);
  const auto s = cell_sizes(f, ModelParams{}, CellMethod::exponential, static_cast<int>(st.range(0)));
  for (auto _ : st) benchmark::DoNotOptimize(evaluate_model(f, ModelParams{}, s));
}
BENCHMARK(BM_EvaluateModel)->Arg(4)->Arg(43)->Unit(benchmark::kMicrosecond);

static void BM_EmpiricalOptimal(benchmark::State& st) {
  const Empirical e(PowerLaw(-3.0, 100.0).sample(static_cast<std::size_t>(st.range(0)), 1));
  ModelParams p;
  p.nu = 0.6;
  for (auto _ : st) benchmark::DoNotOptimize(choose_cell_sizes(e, p, CellMethod::optimal));
}
BENCHMARK(BM_EmpiricalOptimal)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
