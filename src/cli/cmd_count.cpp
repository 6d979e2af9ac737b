// hgrid count: one measurement of the HGrid on a packing file
// (measure/measurement.hpp), printed from its table of fields.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "hgridlab/calibration/calibration.hpp"
#include "grid_options.hpp"
#include "hgridlab/measure/balance.hpp"
#include "hgridlab/measure/fields.hpp"
#include "hgridlab/measure/measurement.hpp"

namespace hgrid::cli {
namespace {

/// --balance P1,P2,...: the simulated load balance of the query on P threads
/// (measure/balance.hpp), priced by this machine's time model if stored.
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
               const std::string& balance, const std::string& model) {
  const double K = resolve_K(K_text, "K");
  const Predictions predictions = parse_predictions(model);
  const WallPairs wall_pairs = parse_wall_pairs(o.wall_pairs);
  if (repeat < 0) throw InputError("repeat", "must be >= 0");
  if (o.decompose) {
    if (repeat > 0 || !balance.empty()) throw InputError(repeat > 0 ? "repeat" : "balance", "not with --decompose");
    return run_decomposed_count(o.file, decomposed_params(o), K, as_json);
  }
  const Packing p = read_grid_packing(o);
  const GridParams g = resolve(o, p, K);
  MeasureOptions mo;
  mo.K = K;
  mo.predict(predictions);
  mo.model_progress = true;
  mo.wall_pairs = wall_pairs;
  if (!(o.excluded_budget >= 0)) throw InputError("excluded-budget", "must be >= 0 (0: no budget)");
  mo.excluded_work_budget = o.excluded_budget;
  if (repeat > 0) mo.timing = TimingOptions{repeat, repeat, 0.0};
  const std::optional<Calibration> cal = stored_calibration();
  if (const TimeModelFit* t = cal ? cal->time_model(p.d) : nullptr) {
    mo.time_model = t->coef;
    mo.time_model_source = "calibration of " + cal->date + " on " + cal->machine;
  }
  const Measurement m = measure(p, g, mo);
  const BalanceRun b = balance.empty() ? BalanceRun{} : balance_of(p, g, balance, K);
  if (!as_json) {
    std::fputs(measurement_text(m).c_str(), stdout);
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

void register_count_commands(CLI::App& app) {
  {
    auto o = std::make_shared<GridOptions>();
    auto K = std::make_shared<std::string>("0.2");
    auto repeat = std::make_shared<int>(0);
    auto js = std::make_shared<bool>(false);
    auto balance = std::make_shared<std::string>();
    auto model = std::make_shared<std::string>("excluded");
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
    sub->add_option("--excluded-budget", o->excluded_budget,
                    "2D: the most multiply-adds the excluded-volume model's numerical solution may take (6e9: about "
                    "a second on one core; 0: no budget, up to a minute at omega = 50)")
        ->default_val(kDiscWorkPerSecond);
    sub->add_option("--model", *model,
                    "predictions beside the counts: excluded (the paper's model and the excluded-volume model), "
                    "paper (the paper's alone), none")
        ->default_val("excluded");
    sub->add_flag("--json", *js, "print one JSON object (its fields: `hgrid fields`, docs/MEASUREMENT.md)");
    sub->callback([o, K, repeat, js, balance, model] { run_count(*o, *K, *repeat, *js, *balance, *model); });
  }
}

}  // namespace hgrid::cli
