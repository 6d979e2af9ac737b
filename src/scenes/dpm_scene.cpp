// The DPM free-cooling comparison (paper Sect. 5, "Full DPM test"): the same
// initial state simulated with the model's optimal Top-Down HGrid and with
// the linked-cell method (one level), timing the whole run and its contact
// detection; kinetic energy against time; the model's predicted speed-up.
#include "hgridlab/scenes/dpm_scene.hpp"

#include "hgridlab/calibration/calibration.hpp"
#include "hgridlab/model/time_model.hpp"
#include "hgridlab/measure/measurement.hpp"

#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <nlohmann/json.hpp>

#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/model/distribution.hpp"
#include "hgridlab/dpm/haff.hpp"
#include "hgridlab/scenes/dpm_scene_file.hpp"
#include "hgridlab/dpm/simulation.hpp"
#include "hgridlab/base/threads.hpp"
#include "hgridlab/model/model.hpp"
#include "hgridlab/io/provenance.hpp"
#include "hgridlab/io/packing_cache.hpp"
#include "hgridlab/io/result_table.hpp"
#include "hgridlab/base/clock.hpp"
#include "hgridlab/base/progress.hpp"

namespace hgrid::dpm {
namespace {

struct RunResult {
  std::vector<double> sizes;
  double seconds_total = 0;
  StepStats stats;
  std::vector<double> t, E;  // kinetic energy samples
  double T_over_N = 0;       // measured with a counted query on the initial state
  double checks_per_n = 0, accesses_per_n = 0;
  std::uint64_t contacts0 = 0;
  std::vector<double> final_state;  // positions, then velocities, at the last step
};

/// The counted search of the initial state, through the one measurement
/// (measure/measurement.hpp) every command and scene reports from.
Counters measured_counts(const Packing& p, const std::vector<double>& sizes) {
  return measure(p, GridParams{sizes, Search::top_down}).counts;
}

/// The runs of the scene (each a grid's sizes and a contact list's skin:
/// the optimal grid's, the linked cell's, the optimal grid's with a skin)
/// from the same state, interleaved: block by block of sample_every steps,
/// each block timed on its own and the runs' order rotated every block. A
/// phase of the machine (these VMs have slow ones lasting seconds to
/// minutes) then slows every run alike, where runs one after the other
/// could meet different phases; each run is still alone on its core.
std::vector<RunResult> simulate_runs(const DpmScene& sc, const Packing& p, const std::vector<double>& vel,
                                     const std::vector<std::pair<std::vector<double>, double>>& runs, bool progress) {
  const std::size_t R = runs.size();
  std::vector<RunResult> r(R);
  std::vector<std::unique_ptr<Simulation>> sim(R);
  const double n = static_cast<double>(p.size());
  for (std::size_t k = 0; k < R; ++k) {
    const auto& sizes = runs[k].first;
    r[k].sizes = sizes;
    const Counters cnt = measured_counts(p, sizes);
    r[k].T_over_N = cnt.cost(sc.K) / n;
    r[k].contacts0 = cnt.contacts;
    r[k].checks_per_n = static_cast<double>(cnt.narrow_phase_checks) / n;
    r[k].accesses_per_n = static_cast<double>(cnt.cell_accesses) / n;
    DpmConfig c = sc.config;
    c.box = p.box;
    c.sizes = sizes;
    c.search = Search::top_down;
    c.skin = runs[k].second;
    sim[k] = make_simulation(c, p, vel);
    r[k].t.push_back(0);
    r[k].E.push_back(sim[k]->kinetic_energy());
  }
  Progress bar(progress, "  optimal grid, linked cell, contact list: interleaved", "steps");
  std::uint64_t done = 0;
  for (std::size_t block = 0; done < sc.steps; ++block) {
    const std::uint64_t steps = std::min(sc.sample_every, sc.steps - done);
    for (std::size_t j = 0; j < R; ++j) {
      const std::size_t k = (j + block) % R;
      const auto t0 = Clock::now();
      sim[k]->run(steps);
      r[k].t.push_back(sim[k]->time());
      r[k].E.push_back(sim[k]->kinetic_energy());
      r[k].seconds_total += seconds_since(t0);
    }
    done += steps;
    bar.count(static_cast<double>(done), static_cast<double>(sc.steps));
  }
  for (std::size_t k = 0; k < R; ++k) {
    r[k].stats = sim[k]->stats();
    r[k].final_state = sim[k]->positions();
    const auto v = sim[k]->velocities();
    r[k].final_state.insert(r[k].final_state.end(), v.begin(), v.end());
  }
  return r;
}

nlohmann::json run_json(const RunResult& r) {
  return {{"sizes", r.sizes},
          {"levels", r.sizes.size()},
          {"seconds_total", r.seconds_total},
          {"list_builds", r.stats.list_builds},
          {"seconds_contact_detection", r.stats.seconds_contact_detection},
          {"seconds_grid_build", r.stats.seconds_grid_build},
          {"seconds_query", r.stats.seconds_query},
          {"seconds_forces", r.stats.seconds_forces},
          {"seconds_integration", r.stats.seconds_integration},
          {"steps", r.stats.steps},
          {"pair_contacts", r.stats.pair_contacts},
          {"wall_contacts", r.stats.wall_contacts},
          {"friction_evaluations", r.stats.friction_evaluations},
          {"gravity_evaluations", r.stats.gravity_evaluations},
          {"measured_T_over_N_initial", r.T_over_N},
          {"checks_per_particle_initial", r.checks_per_n},
          {"accesses_per_particle_initial", r.accesses_per_n},
          {"energy_final_over_initial", r.E.back() / r.E.front()}};
}

/// The summary as dotted key -> scalar, string or array of numbers (booleans
/// and integers as numbers), in a fixed order.
std::vector<std::pair<std::string, nlohmann::json>> flatten(const nlohmann::json& j, const std::string& prefix = "") {
  std::vector<std::pair<std::string, nlohmann::json>> out;
  for (const auto& [k, v] : j.items()) {
    const std::string key = prefix.empty() ? k : prefix + "." + k;
    if (v.is_object()) {
      for (auto& kv : flatten(v, key)) out.push_back(std::move(kv));
    } else if (v.is_boolean()) {
      out.emplace_back(key, v.get<bool>() ? 1.0 : 0.0);
    } else if (v.is_number()) {
      out.emplace_back(key, v.get<double>());
    } else {
      out.emplace_back(key, v);
    }
  }
  return out;
}

}  // namespace

std::string run_dpm_scene(const std::string& path, const std::string& scale, const RunOptions& opt, bool json) {
  const DpmScene sc = load_dpm_scene(path, scale);
  PackingSpec spec = sc.initial;
  spec.progress = opt.progress;
  std::filesystem::create_directories(opt.packing_dir);
  const Packing p = cached_packing(spec, opt.packing_dir);

  // Initial velocities: independent Gaussian components of std `speed`.
  std::mt19937_64 rng(sc.velocity_seed);
  std::normal_distribution<double> g(0.0, sc.speed);
  std::vector<double> vel(p.size() * p.d);
  for (auto& v : vel) v = g(rng);

  // Cell sizes: the cost model for the scene's distribution (the paper's
  // procedure), K and nu; the linked cell is one level of reference_size.
  const PowerLaw dist(sc.initial.alpha, sc.initial.omega);
  const ModelParams mp{sc.initial.d, sc.initial.nu, sc.K, Search::top_down};
  const SizeChoice choice = choose_cell_sizes(dist, mp, sc.method);
  std::vector<double> opt_sizes = sizes_for_grid(choice.sizes, 2 * sc.initial.omega);
  const std::vector<double> lc_sizes{sc.reference_size};
  const double model_opt = evaluate_model(dist, mp, opt_sizes).T_over_N;
  const double model_lc = evaluate_model(dist, mp, lc_sizes).T_over_N;
  // The same model for this run's own radii and packing fraction.
  const Empirical own(p.radii);
  const ModelParams mp_own{p.d, p.packing_fraction(), sc.K, Search::top_down};
  const double own_ratio = evaluate_model(own, mp_own, lc_sizes).T_over_N / evaluate_model(own, mp_own, opt_sizes).T_over_N;

  if (opt.progress)
    std::cerr << "hgrid run: DPM scene " << sc.name << " (" << scale << " scale): N = " << p.size() << ", "
              << sc.steps << " steps, dt = " << sc.dt_over_tc << " t_c, e = " << sc.config.restitution << "\n";
  // The optimal grid and the linked cell rebuilt every step (the paper's
  // comparison), and the optimal grid's contact list with the scene's skin.
  const std::vector<RunResult> runs =
      simulate_runs(sc, p, vel, {{opt_sizes, 0.0}, {lc_sizes, 0.0}, {opt_sizes, sc.config.skin}}, opt.progress);
  const RunResult &a = runs[0], &b = runs[1], &l = runs[2];
  const HaffFit haff = fit_haff(a.t, a.E);
  // The engine sums forces in canonical pair order, so the grids and the
  // list must give the same simulation, bit for bit: anything else is a bug.
  const bool identical = a.final_state == b.final_state && a.E == b.E;
  const bool list_identical = a.final_state == l.final_state && a.E == l.E;
  if (!identical || !list_identical)
    std::cerr << "hgrid run: warning: the optimal-grid, linked-cell and contact-list runs of " << sc.name
              << " ended in different states (the engine should depend on neither grid nor skin)\n";
  // This solver's own overhead factor (paper Sect. 7: use the K of your
  // solver): query seconds per particle-step = c_check * checks + c_access *
  // accesses, solved from the two runs' initial counts; K_eff = c_access / c_check.
  const double steps_n = static_cast<double>(sc.steps) * static_cast<double>(p.size());
  const double qa = a.stats.seconds_query / steps_n, qb = b.stats.seconds_query / steps_n;
  const double det = a.checks_per_n * b.accesses_per_n - b.checks_per_n * a.accesses_per_n;
  const double c_check = (qa * b.accesses_per_n - qb * a.accesses_per_n) / det;
  const double c_access = (a.checks_per_n * qb - b.checks_per_n * qa) / det;

  nlohmann::json out = {
      {"scene", sc.name},
      {"scale", scale},
      {"source", sc.source},
      {"n", p.size()},
      {"d", p.d},
      {"nu", p.packing_fraction()},
      {"alpha", sc.initial.alpha},
      {"omega", sc.initial.omega},
      {"boundary", to_string(p.boundary)},
      {"placement", to_string(sc.initial.placement)},
      {"packing_seed", sc.initial.seed},
      {"velocity_seed", sc.velocity_seed},
      {"restitution", sc.config.restitution},
      {"contact_time", sc.config.contact_time},
      {"dt_over_tc", sc.dt_over_tc},
      {"steps", sc.steps},
      {"threads", resolve_threads(sc.config.threads)},
      {"skin", sc.config.skin},
      {"friction", sc.config.friction},
      {"tangential", sc.config.friction ? to_string(sc.config.tangential) : "none"},
      {"gravity", sc.config.gravity},
      {"K", sc.K},
      {"optimal", run_json(a)},
      {"linked_cell", run_json(b)},
      {"trajectories_identical", identical},
      {"contact_list", run_json(l)},
      {"list_trajectory_identical", list_identical},
      {"speedup_list_contact_detection", a.stats.seconds_contact_detection / l.stats.seconds_contact_detection},
      {"speedup_list_total", a.seconds_total / l.seconds_total},
      {"model_T_over_N_optimal", model_opt},
      {"model_T_over_N_linked_cell", model_lc},
      {"predicted_speedup_contact_detection", model_lc / model_opt},
      {"predicted_speedup_contact_detection_own_radii", own_ratio},
      {"measured_count_ratio", b.T_over_N / a.T_over_N},
      {"speedup_contact_detection", b.stats.seconds_contact_detection / a.stats.seconds_contact_detection},
      {"speedup_query", b.stats.seconds_query / a.stats.seconds_query},
      {"speedup_total", b.seconds_total / a.seconds_total},
      {"seconds_per_check", c_check},
      {"seconds_per_access", c_access},
      {"K_effective", c_access / c_check},
      {"haff", {{"t0", haff.t0}, {"E0", haff.E0}, {"r2", haff.r2}}},
  };
  // The time model's contact-detection speed-up (build + query per step) for
  // the two grids on this run's radii, with this machine's calibration.
  const std::optional<Calibration> cal = stored_calibration();
  if (const TimeModelFit* t = cal ? cal->time_model(p.d) : nullptr) {
    const double n = static_cast<double>(p.size());
    const double lc = predict_seconds(t->coef, expected_time_terms(own, mp_own, lc_sizes, n)).total();
    const double og = predict_seconds(t->coef, expected_time_terms(own, mp_own, opt_sizes, n)).total();
    out["predicted_speedup_seconds"] = lc / og;
    out["time_model"] = "calibration of " + cal->date + " on " + cal->machine;
  } else {
    out["time_model"] = "none: no calibration with a " + std::to_string(p.d) + "D time model (run hgrid calibrate)";
  }
  for (const auto& [k, v] : provenance_fields()) out[k] = v;

  std::filesystem::create_directories(opt.results_dir);
  const std::string stem = opt.results_dir + "/" + sc.name + (scale == "default" ? "" : "-" + scale);
  std::vector<double> haff_E(a.t.size()), lc_E(a.t.size(), std::nan(""));
  for (std::size_t i = 0; i < a.t.size(); ++i) {
    haff_E[i] = haff.E0 / ((1 + a.t[i] / haff.t0) * (1 + a.t[i] / haff.t0));
    if (i < b.E.size()) lc_E[i] = b.E[i];
  }
  const auto flat = flatten(out);
  // The energy curves as columns; the summary as the HDF5 file's root
  // attributes and the CSV's "# key=value" lines (what plots/dpm.sh renders).
  ResultTable t;
  t.csv_precision = 10;
  t.columns = {{"t", a.t}, {"E_optimal", a.E}, {"E_linked_cell", lc_E}, {"E_haff", haff_E}};
  for (const auto& [k, v] : flat) {
    if (v.is_string()) t.attributes.emplace_back(k, v.get<std::string>());
    else if (v.is_array()) t.attributes.emplace_back(k, v.get<std::vector<double>>());
    else t.attributes.emplace_back(k, std::vector<double>{v.get<double>()});
    if (k == "source") continue;  // multi-line: in the HDF5 file only
    std::ostringstream line;
    line.precision(t.csv_precision);
    line << k << "=";
    if (v.is_string()) line << v.get<std::string>();
    else if (v.is_array()) {
      for (std::size_t i = 0; i < v.size(); ++i) line << (i ? ";" : "") << v[i].get<double>();
    } else line << v.get<double>();
    t.csv_comments.push_back(line.str());
  }
  write_result_table(stem, t);

  if (json) return out.dump(2) + "\n";
  std::ostringstream line;
  line << sc.name << " (" << scale << "): speed-up contact detection "
       << out["speedup_contact_detection"].get<double>() << " (predicted "
       << out["predicted_speedup_contact_detection"].get<double>()
       << (out.contains("predicted_speedup_seconds")
               ? "; time model " + format_number(out["predicted_speedup_seconds"].get<double>())
               : std::string())
       << "), whole run " << out["speedup_total"].get<double>() << "; contact list (skin " << sc.config.skin
       << ") over the optimal grid rebuilt every step: contact detection "
       << out["speedup_list_contact_detection"].get<double>() << ", whole run " << out["speedup_list_total"].get<double>()
       << "; results in " << stem << ".h5 and .csv\n";
  return line.str();
}

}  // namespace hgrid::dpm
