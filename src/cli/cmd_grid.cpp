// hgrid pairs / hgrid count: the HGrid on a packing file.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "packing/packing_sizes.hpp"
#include "grid/brute_force.hpp"
#include "experiment/balance.hpp"
#include "experiment/calibration.hpp"
#include "grid/dispatch.hpp"
#include "grid/hgrid.hpp"
#include "packing/packing.hpp"
#include "io/packing_file.hpp"
#include "io/particle_file.hpp"
#include "measure/fields.hpp"
#include "measure/measurement.hpp"
#include "model/excluded.hpp"
#include "model/time_model.hpp"

namespace hgrid::cli {
namespace {

struct GridOptions {
  std::string file;
  std::optional<std::int64_t> frame;
  std::optional<int> d;  // the file's dimension, checked when given
  std::string sizes;
  std::string search = "topdown";
  std::string cost = "count";
  std::string cells;  // a cell-size method, parsed in resolve()
  SizeRequest request;
  int threads = 0;  // 0: all cores (OMP_NUM_THREADS)
  bool decompose = false;  // over the ranks of an MPI run (cmd_decompose.cpp)
  std::string wall_pairs = "layer";  // count: the excluded-volume model's pairs near a wall
};

void add_grid_options(CLI::App* sub, GridOptions& o) {
  sub->add_option("FILE", o.file, "packing file (HDF5, CSV/text, LAMMPS data or dump, MercuryDPM .data)")->required();
  add_frame_option(sub, o.frame);
  sub->add_option("--d", o.d, "the file's dimension, 2 or 3: refused if the file's differs (default: the file's)");
  auto* sizes = sub->add_option("--sizes", o.sizes, "cell sizes s1,s2,...,sL (increasing, same unit as the radii)");
  auto* cells = sub->add_option("--cells", o.cells,
                                "choose the sizes with the cost model: linear|exponential|constant|optimal");
  sizes->excludes(cells);
  sub->add_option("--levels", o.request.levels, "with --cells: number of levels L (default: the best L*)");
  sub->add_option("--q", o.request.q, "with --cells constant: ratio of particles per cell between levels")
      ->default_val(1.0);
  sub->add_option("--search", o.search, "cross-level search: topdown|bottomup")->default_val("topdown");
  sub->add_option("--cost", o.cost,
                  "with --cells optimal: what the sizes minimise: count (the paper's T = checks + K accesses) or "
                  "time (this machine's predicted seconds of build + query; needs `hgrid calibrate`)")
      ->default_val("count");
  sub->add_flag("--excluded-sizes", o.request.excluded_model,
                "with --cells optimal: refine the sizes under the excluded-volume model (hard-sphere packings; 2D: omega <= 50)");
  add_threads_option(sub, o.threads);
  sub->add_flag("--decompose", o.decompose,
                "under mpirun/srun: split the box into one brick per rank, each searched by its rank with the "
                "ghosts it needs (needs --sizes; without MPI: one rank)");
}

/// The params of a decomposed search: --sizes only (choosing sizes needs
/// every radius on one rank: `hgrid recommend FILE` prints them).
GridParams decomposed_params(const GridOptions& o) {
  if (o.sizes.empty())
    throw InputError("sizes", "--decompose needs --sizes s1,...,sL (`hgrid recommend FILE` prints good ones)");
  if (parse_cost(o.cost) == CostKind::time) throw InputError("cost", "'time' chooses sizes: not with --decompose");
  return GridParams{parse_list(o.sizes, "sizes"), parse_search(o.search), threads_per_rank(check_threads(o.threads))};
}

GridParams resolve(const GridOptions& o, const Packing& p, double K) {
  GridParams g;
  g.search = parse_search(o.search);
  g.threads = check_threads(o.threads);
  if (!o.sizes.empty()) {
    g.sizes = parse_list(o.sizes, "sizes");
  } else if (!o.cells.empty()) {
    SizeRequest r = o.request;
    r.method = parse_cell_method(o.cells);
    if (parse_cost(o.cost) == CostKind::time) r.time_model = calibrated_time_model(p.d, "cost").coef;
    g.sizes = model_sizes(p, r, g.search, K);
  } else {
    throw InputError("sizes", "give --sizes s1,...,sL or --cells METHOD");
  }
  if (parse_cost(o.cost) == CostKind::time && o.cells.empty())
    throw InputError("cost", "'time' chooses sizes: give --cells optimal instead of --sizes");
  return g;
}

void run_pairs(const GridOptions& o, bool brute) {
  if (o.decompose) {
    if (brute) throw InputError("brute", "not with --decompose");
    return run_decomposed_pairs(o.file, decomposed_params(o));
  }
  const Packing p = read_packing(o.file, Isolation::child_process, kIsolatedReadBaseSeconds, o.frame);
  check_file_dimension(p.d, o.d, o.file);
  const GridParams g = brute ? GridParams{} : resolve(o, p, 0.2);
  dispatch(p.d, p.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    constexpr Boundary B = decltype(bnd)::value;
    const auto spheres = p.spheres<D>();
    if (brute) {
      PairWriter out;
      brute_force_pairs<D, B>(std::span<const Sphere<D>>(spheres), p.extent<D>(), out);
    } else {
      // One writer per thread; each writes whole lines, so the lines of
      // several threads never mix (their order does differ between runs).
      const HGrid<D, B> grid(spheres, p.extent<D>(), g);
      std::vector<PairWriter> out(static_cast<std::size_t>(resolve_threads(g.threads)));
      grid.for_each_pair([&](int t, std::uint32_t i, std::uint32_t j) { out[static_cast<std::size_t>(t)](i, j); });
    }
  });
}

/// The text form of `count`: the record's per-level table and totals.
void print_count(const Measurement& m) {
  std::printf("n = %llu, d = %d, %s%s, nu = %.6g, search %s, K = %g\n", (unsigned long long)m.n, m.d,
              to_string(m.boundary), m.boundary_assumed ? " (not in the file: assumed)" : "", m.nu_achieved,
              to_string(m.search), m.K);
  const bool ex = !m.model_excluded_checks_by_level.empty();
  const auto L = static_cast<std::size_t>(m.counts.levels);
  const auto row_sum = [L](const auto& v, std::size_t h) {
    double s = 0;
    for (std::size_t k = 0; k < L && h * L + k < v.size(); ++k) s += static_cast<double>(v[h * L + k]);
    return s;
  };
  // The models' columns: expected narrow-phase checks of the level's particles.
  std::printf("%5s %14s %12s %16s %20s %14s %16s\n", "level", "size", "particles", "cell_accesses", "narrow_phase_checks",
              "model_checks", "excluded_checks");
  for (std::size_t h = 0; h < L; ++h)
    std::printf("%5zu %14.6g %12llu %16.0f %20.0f %14.6g %16s\n", h + 1, m.sizes[h],
                (unsigned long long)m.counts.particles_per_level[h], row_sum(m.counts.accesses_by_level, h),
                row_sum(m.counts.checks_by_level, h), row_sum(m.model_checks_by_level, h),
                ex ? std::to_string(row_sum(m.model_excluded_checks_by_level, h)).c_str() : "-");
  std::printf("total: %llu cell accesses, %llu narrow-phase checks, %llu contacts, T/N = %.6g\n",
              (unsigned long long)m.counts.cell_accesses, (unsigned long long)m.counts.narrow_phase_checks,
              (unsigned long long)m.counts.contacts, m.T_over_N);
  std::printf("model T/N = %.6g (random centres)", m.model_T_over_N);
  if (ex)
    std::printf(", %.6g (excluded volume)\n", m.model_excluded_T_over_N);
  else
    std::printf("; excluded-volume model: %s\n", m.model_excluded_skipped.c_str());
  if (m.repeats > 0)
    std::printf("wall time, fastest of %d uncounted runs on %d threads: query %.6g s, build %.6g s\n", m.repeats,
                m.threads, m.seconds_query_best, m.seconds_build_best);
  if (!m.time_model.empty())
    std::printf("time model (%s), one thread: query %.6g s, build %.6g s (from the counts: %.6g s, %.6g s)\n",
                m.time_model.c_str(), m.predicted_seconds_query_one_thread, m.predicted_seconds_build_one_thread,
                m.predicted_seconds_query_one_thread_from_counts, m.predicted_seconds_build_one_thread_from_counts);
}

/// --balance P1,P2,...: the simulated load balance of the query on P threads
/// (experiment/balance.hpp), priced by this machine's time model if stored.
struct BalanceRun {
  std::vector<Balance> rows;
  std::string cost;
};
BalanceRun balance_of(const Packing& p, const GridParams& g, const std::string& list, double K) {
  std::vector<int> threads;
  for (const double v : parse_list(list, "balance")) {
    if (!(v >= 1 && v <= 1e6 && v == std::floor(v)))
      throw InputError("balance", "thread counts must be whole numbers from 1 to 1000000");
    threads.push_back(static_cast<int>(v));
  }
  BalanceCost cost;
  cost.K = K;
  const std::optional<Calibration> cal = stored_calibration();
  if (const TimeModelFit* t = cal ? cal->time_model(p.d) : nullptr) cost.coef = t->coef;
  return {simulate_balance(p, g, threads, cost), cost.name()};
}

void run_count(const GridOptions& o, const std::string& K_text, int repeat, bool as_json,
               const std::string& balance) {
  const double K = resolve_K(K_text, "K");
  const WallPairs wall_pairs = parse_wall_pairs(o.wall_pairs);
  if (repeat < 0) throw InputError("repeat", "must be >= 0");
  if (o.decompose) {
    if (repeat > 0 || !balance.empty()) throw InputError(repeat > 0 ? "repeat" : "balance", "not with --decompose");
    return run_decomposed_count(o.file, decomposed_params(o), K, as_json);
  }
  const Packing p = read_packing(o.file, Isolation::child_process, kIsolatedReadBaseSeconds, o.frame);
  check_file_dimension(p.d, o.d, o.file);
  const GridParams g = resolve(o, p, K);
  MeasureOptions mo;
  mo.K = K;
  mo.model = mo.excluded_model = mo.model_progress = true;
  mo.wall_pairs = wall_pairs;
  if (repeat > 0) mo.timing = TimingOptions{repeat, repeat, 0.0};
  const std::optional<Calibration> cal = stored_calibration();
  if (const TimeModelFit* t = cal ? cal->time_model(p.d) : nullptr) {
    mo.time_model = t->coef;
    mo.time_model_source = "calibration of " + cal->date + " on " + cal->machine;
  }
  const Measurement m = measure(p, g, mo);
  const BalanceRun b = balance.empty() ? BalanceRun{} : balance_of(p, g, balance, K);
  if (!as_json) {
    print_count(m);
    for (const Balance& r : b.rows)
      std::printf("simulated on %d threads (%zu pieces, %s): imbalance %.2f %%, largest piece %.3g of a thread's share\n",
                  r.threads, r.pieces, b.cost.c_str(), 100 * r.imbalance, r.largest_piece);
    return;
  }
  auto j = nlohmann::ordered_json::parse(measurement_json(m));
  if (!balance.empty()) {
    j["balance"] = nlohmann::ordered_json::array();
    for (const Balance& r : b.rows)
      j["balance"].push_back({{"threads", r.threads}, {"pieces", r.pieces}, {"imbalance", r.imbalance},
                              {"largest_piece", r.largest_piece}});
    j["balance_cost"] = b.cost;
  }
  std::cout << j.dump(2) << "\n";
}

}  // namespace

void register_grid_commands(CLI::App& app) {
  {
    auto md = std::make_shared<bool>(false);
    auto* sub = app.add_subcommand("fields", "the fields of a measurement (count --json, result files, Python's count)");
    sub->add_flag("--markdown", *md, "as a Markdown table (docs/MEASUREMENT.md)");
    sub->callback([md] {
      if (*md) std::printf("| field | unit | meaning |\n|---|---|---|\n");
      for (const MeasurementField& f : measurement_fields())
        std::printf(*md ? "| `%s` | %s | %s |\n" : "%-48s %-7s %s\n", f.name, *f.unit ? f.unit : "-", f.meaning);
    });
  }
  {
    auto o = std::make_shared<GridOptions>();
    auto brute = std::make_shared<bool>(false);
    auto* sub = app.add_subcommand("pairs", "print every overlapping pair 'i j' (0-based, i < j), one per line");
    add_grid_options(sub, *o);
    sub->add_flag("--brute", *brute, "use the O(N^2) brute force instead of the HGrid");
    sub->callback([o, brute] { run_pairs(*o, *brute); });
  }
  {
    auto o = std::make_shared<GridOptions>();
    auto K = std::make_shared<std::string>("0.2");
    auto repeat = std::make_shared<int>(0);
    auto js = std::make_shared<bool>(false);
    auto balance = std::make_shared<std::string>();
    auto* sub = app.add_subcommand("count", "count cell accesses and narrow-phase checks of one contact search");
    add_grid_options(sub, *o);
    sub->add_option("--K", *K, std::string("for T = checks + K accesses and --cells: ") + kKHelp)
        ->default_val("0.2");
    sub->add_option("--repeat", *repeat,
                    "also time R uncounted build + query runs and report the fastest (seconds_*_best)")
        ->default_val(0);
    sub->add_option("--balance", *balance,
                    "P1,P2,...: simulate the query's load balance on P threads from the counted work of each piece "
                    "of its decomposition (JSON balance: imbalance = simulated time / (work / P) - 1)");
    sub->add_option("--wall-pairs", o->wall_pairs,
                    "walls, excluded-volume model: layer (no pair excess for centres within the largest radius of a "
                    "wall; docs/MODEL.md section 8) or product (Kirkwood's superposition everywhere)")
        ->default_val("layer");
    sub->add_flag("--json", *js, "print one JSON object (its fields: `hgrid fields`, docs/MEASUREMENT.md)");
    sub->callback([o, K, repeat, js, balance] { run_count(*o, *K, *repeat, *js, *balance); });
  }
}

}  // namespace hgrid::cli
