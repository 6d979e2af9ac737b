// hgrid pairs / hgrid count: the HGrid on a packing file.
#include <cmath>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "packing/packing_model.hpp"
#include "packing/packing_sizes.hpp"
#include "grid/brute_force.hpp"
#include "experiment/balance.hpp"
#include "experiment/calibration.hpp"
#include "grid/dispatch.hpp"
#include "grid/hgrid.hpp"
#include "packing/packing.hpp"
#include "experiment/timing.hpp"
#include "io/packing_file.hpp"
#include "io/particle_file.hpp"
#include "model/distribution.hpp"
#include "model/excluded.hpp"
#include "model/time_model.hpp"

namespace hgrid::cli {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

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

nlohmann::json count_json(const Packing& p, const GridParams& g, const std::vector<double>& used, const Counters& c,
                          double K, double t_build, double t_query, WallPairs wall_pairs) {
  using nlohmann::json;
  const double n = static_cast<double>(p.size());
  json j;
  j["n"] = p.size();
  j["d"] = p.d;
  j["boundary"] = to_string(p.boundary);
  j["boundary_source"] = boundary_description(p) == to_string(p.boundary) ? "file" : kBoundaryAssumed;
  j["packing_fraction"] = p.packing_fraction();
  j["search"] = to_string(g.search);
  j["threads"] = resolve_threads(g.threads);
  j["K"] = K;
  j["sizes_requested"] = g.sizes;
  j["sizes"] = used;
  j["levels"] = c.levels;
  j["cell_accesses"] = c.cell_accesses;
  j["narrow_phase_checks"] = c.narrow_phase_checks;
  j["contacts"] = c.contacts;
  j["T_over_N"] = n > 0 ? c.cost(K) / n : 0.0;
  j["T_cd_over_N"] = n > 0 ? static_cast<double>(c.narrow_phase_checks) / n : 0.0;
  j["T_ca_over_N"] = n > 0 ? static_cast<double>(c.cell_accesses) / n : 0.0;
  const PackingModels models = model_for_packing(p, used, g.search, K, true, true, wall_pairs);
  if (p.boundary == Boundary::walls) j["wall_pairs"] = to_string(wall_pairs);
  j["model_T_over_N"] = models.random.T_over_N;
  j["model_T_cd_over_N"] = models.random.T_cd_over_N;
  j["model_T_ca_over_N"] = models.random.T_ca_over_N;
  if (models.excluded) {
    j["model_excluded_T_over_N"] = models.excluded->T_over_N;
    j["model_excluded_T_cd_over_N"] = models.excluded->T_cd_over_N;
  } else {
    j["model_excluded_T_over_N"] = nullptr;
    j["model_excluded_skipped"] = models.excluded_skipped;
  }
  json levels = json::array();
  const int L = c.levels;
  for (int h = 0; h < L; ++h) {
    json row;
    row["level"] = h + 1;
    row["size"] = used[h];
    row["particles"] = c.particles_per_level[h];
    std::uint64_t acc = 0, chk = 0;
    json acc_row = json::array(), chk_row = json::array();
    for (int k = 0; k < L; ++k) {
      acc += c.accesses_by_level[h * L + k];
      chk += c.checks_by_level[h * L + k];
      acc_row.push_back(c.accesses_by_level[h * L + k]);
      chk_row.push_back(c.checks_by_level[h * L + k]);
    }
    row["cell_accesses"] = acc;
    row["narrow_phase_checks"] = chk;
    row["cell_accesses_by_level_searched"] = acc_row;
    row["narrow_phase_checks_by_level_searched"] = chk_row;
    // The models' expected checks (counts, like the measurement).
    json mr = json::array(), me = json::array();
    for (int k = 0; k < L; ++k) {
      mr.push_back(n * models.random.T_cd_pair[h * L + k]);
      if (models.excluded) me.push_back(n * models.excluded->T_cd_pair[h * L + k]);
    }
    row["model_narrow_phase_checks_by_level_searched"] = mr;
    if (models.excluded) row["model_excluded_narrow_phase_checks_by_level_searched"] = me;
    levels.push_back(row);
  }
  j["per_level"] = levels;
  j["seconds_build"] = t_build;
  j["seconds_query"] = t_query;
  return j;
}

/// The time model's seconds (this machine's calibration) for the sizes used:
/// predicted from the model's expected terms (predicted_seconds_*) and from
/// the terms this query counted (predicted_seconds_*_from_counts).
void add_predicted_seconds(nlohmann::json& j, const Packing& p, const std::vector<double>& used, Search search,
                           double K, const TimeTerms& counted) {
  const std::optional<Calibration> cal = stored_calibration();
  const TimeModelFit* t = cal ? cal->time_model(p.d) : nullptr;
  if (!t) {
    j["time_model"] = "none: no calibration with a " + std::to_string(p.d) + "D time model at " + calibration_path() +
                      " (run `hgrid calibrate`)";
    return;
  }
  j["time_model"] = "calibration of " + cal->date + " on " + cal->machine + " (seconds on one thread)";
  const Empirical dist(p.radii);
  const ModelParams mp{p.d, p.packing_fraction(), K, search};
  const PredictedSeconds e = predict_seconds(t->coef, expected_time_terms(dist, mp, used, double(p.size())));
  const PredictedSeconds c = predict_seconds(t->coef, counted);
  j["predicted_seconds_build"] = e.build;
  j["predicted_seconds_query"] = e.query;
  j["predicted_seconds_build_from_counts"] = c.build;
  j["predicted_seconds_query_from_counts"] = c.query;
}

void print_count_table(const nlohmann::json& j) {
  std::printf("n = %zu, d = %d, %s%s, nu = %.6g, search %s, K = %g\n", j["n"].get<std::size_t>(), j["d"].get<int>(),
              j["boundary"].get<std::string>().c_str(),
              j["boundary_source"] == "file" ? "" : " (not in the file: assumed)", j["packing_fraction"].get<double>(),
              j["search"].get<std::string>().c_str(), j["K"].get<double>());
  const bool ex = !j["model_excluded_T_over_N"].is_null();
  // The models' columns: expected narrow-phase checks of the level's particles.
  std::printf("%5s %14s %12s %16s %20s %14s %16s\n", "level", "size", "particles", "cell_accesses", "narrow_phase_checks",
              "model_checks", "excluded_checks");
  for (const auto& row : j["per_level"]) {
    double mr = 0, me = 0;
    for (const auto& v : row["model_narrow_phase_checks_by_level_searched"]) mr += v.get<double>();
    if (ex)
      for (const auto& v : row["model_excluded_narrow_phase_checks_by_level_searched"]) me += v.get<double>();
    std::printf("%5d %14.6g %12llu %16llu %20llu %14.6g %16s\n", row["level"].get<int>(), row["size"].get<double>(),
                row["particles"].get<unsigned long long>(), row["cell_accesses"].get<unsigned long long>(),
                row["narrow_phase_checks"].get<unsigned long long>(), mr,
                ex ? std::to_string(me).c_str() : "-");
  }
  std::printf("total: %llu cell accesses, %llu narrow-phase checks, %llu contacts, T/N = %.6g\n",
              j["cell_accesses"].get<unsigned long long>(), j["narrow_phase_checks"].get<unsigned long long>(),
              j["contacts"].get<unsigned long long>(), j["T_over_N"].get<double>());
  std::printf("model T/N = %.6g (random centres)", j["model_T_over_N"].get<double>());
  if (ex)
    std::printf(", %.6g (excluded volume)\n", j["model_excluded_T_over_N"].get<double>());
  else
    std::printf("; excluded-volume model: %s\n", j["model_excluded_skipped"].get<std::string>().c_str());
}

/// --balance P1,P2,...: the simulated load balance of the query on P threads
/// (experiment/balance.hpp), priced by this machine's time model if stored.
nlohmann::json balance_json(const Packing& p, const GridParams& g, const std::string& list, double K) {
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
  nlohmann::json out = nlohmann::json::array();
  for (const Balance& b : simulate_balance(p, g, threads, cost))
    out.push_back({{"threads", b.threads}, {"pieces", b.pieces}, {"imbalance", b.imbalance},
                   {"largest_piece", b.largest_piece}});
  return {{"balance", out}, {"balance_cost", cost.name()}};
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
  nlohmann::json j = dispatch(p.d, p.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    constexpr Boundary B = decltype(bnd)::value;
    const auto spheres = p.spheres<D>();
    auto t0 = Clock::now();
    const HGrid<D, B> grid(spheres, p.extent<D>(), g);
    const double t_build = seconds_since(t0);
    t0 = Clock::now();
    const Counters c = grid.template for_each_pair<Counted>([](std::uint32_t, std::uint32_t) {});
    const double t_query = seconds_since(t0);
    nlohmann::json out = count_json(p, g, grid.sizes(), c, K, t_build, t_query, wall_pairs);
    add_predicted_seconds(out, p, grid.sizes(), g.search, K, counted_time_terms(c, build_work(grid)));
    return out;
  });
  if (!balance.empty()) j.update(balance_json(p, g, balance, K));
  if (repeat > 0) {
    const QueryTiming t = time_query(p, g, TimingOptions{repeat, repeat, 0.0});
    j["repeats"] = t.repeats;
    j["seconds_query_best"] = t.query_seconds;
    j["seconds_query_median"] = t.median_query_seconds;
    j["seconds_build_best"] = t.build_seconds;
  }
  if (as_json)
    std::cout << j.dump(2) << "\n";
  else
    print_count_table(j);
  if (!as_json && repeat > 0)
    std::printf("wall time, fastest of %d uncounted runs: query %.6g s, build %.6g s\n", repeat,
                j["seconds_query_best"].get<double>(), j["seconds_build_best"].get<double>());
  if (!as_json && j.contains("balance"))
    for (const auto& b : j["balance"])
      std::printf("simulated on %d threads (%zu pieces, %s): imbalance %.2f %%, largest piece %.3g of a thread's share\n",
                  b["threads"].get<int>(), b["pieces"].get<std::size_t>(), j["balance_cost"].get<std::string>().c_str(),
                  100 * b["imbalance"].get<double>(), b["largest_piece"].get<double>());
  if (!as_json && j.contains("predicted_seconds_query"))
    std::printf("time model (%s): query %.6g s, build %.6g s (from the counts: %.6g s, %.6g s)\n",
                j["time_model"].get<std::string>().c_str(), j["predicted_seconds_query"].get<double>(),
                j["predicted_seconds_build"].get<double>(), j["predicted_seconds_query_from_counts"].get<double>(),
                j["predicted_seconds_build_from_counts"].get<double>());
}

}  // namespace

void register_grid_commands(CLI::App& app) {
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
    sub->add_flag("--json", *js, "print one JSON object");
    sub->callback([o, K, repeat, js, balance] { run_count(*o, *K, *repeat, *js, *balance); });
  }
}

}  // namespace hgrid::cli
