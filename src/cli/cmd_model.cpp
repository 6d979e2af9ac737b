// `hgrid model` (the analytic cost model for one distribution) and
// `hgrid modelfigs` (the data behind the paper's Figs. 2-10).
#include <filesystem>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/common.hpp"
#include "io/atomic_file.hpp"
#include "experiment/calibration.hpp"
#include "model/cell_sizes.hpp"
#include "model/excluded.hpp"
#include "packing/packing_model.hpp"
#include "packing/generate.hpp"
#include "packing/packing_sizes.hpp"
#include "model/figures.hpp"
#include "grid/error.hpp"
#include "packing/packing.hpp"
#include "io/packing_file.hpp"
#include "io/particle_file.hpp"

namespace hgrid::cli {

namespace {

struct ModelOptions {
  int d = 3;
  double nu = 0.7, alpha = -3.0, omega = 100.0, q = 1.0, sigma = 1.0;
  std::string K = "0.2", search = "topdown", cells = "optimal", dist = "powerlaw", radii_file, placement = "random";
  std::string cost = "count";
  double n = 1e6;  // particles, for --cost time
  int levels = 0;  // 0: search L*
  bool json = false, excluded_sizes = false;
  bool d_given = false, nu_given = false;  // --d, --nu on the command line (else, with --radii, the file's)
};

std::unique_ptr<Distribution> make_distribution(const ModelOptions& o, const std::optional<ParticleSet>& file) {
  if (file) return std::make_unique<Empirical>(file->radii);
  if (o.dist == "powerlaw") return std::make_unique<PowerLaw>(o.alpha, o.omega);
  if (o.dist == "lognormal") return std::make_unique<LogNormal>(LogNormal::centred(o.sigma, o.omega));
  throw InputError("dist", "must be powerlaw or lognormal (got '" + o.dist + "')");
}

void run_model(const ModelOptions& o) {
  if (!std::isfinite(o.alpha)) throw InputError("alpha", "must be a finite number");
  // With --radii, d and nu come from the file (its columns, its box) unless
  // given; a file without a box needs --nu (no silent default).
  std::optional<ParticleSet> file;
  if (!o.radii_file.empty()) file = read_particles(o.radii_file, Isolation::child_process);
  const bool file_has_d = file && (file->d == 2 || file->d == 3);  // else --d, default 3, as without --radii
  const FileInputs in = file ? file_inputs(*file, o.radii_file, o.d_given || !file_has_d ? std::optional<int>(o.d) : std::nullopt,
                                           o.nu_given ? std::optional<double>(o.nu) : std::nullopt)
                             : FileInputs{o.d, o.nu, false};
  ModelParams p;
  p.d = in.d;
  p.nu = in.nu;
  p.K = resolve_K(o.K, "K");
  p.search = parse_search(o.search);
  validate(p);
  const CellMethod method = parse_cell_method(o.cells);
  const auto dist = make_distribution(o, file);
  auto choice = choose_cell_sizes(*dist, p, method, o.levels > 0 ? std::optional<int>(o.levels) : std::nullopt, o.q);
  std::optional<PredictedSeconds> seconds;  // --cost time: the time model's optimum replaces the count's
  if (parse_cost(o.cost) == CostKind::time) {
    if (method != CellMethod::optimal || o.levels > 0 || o.excluded_sizes)
      throw InputError("cost", "'time' needs --cells optimal, without --levels or --excluded-sizes");
    if (!(o.n >= 1 && o.n <= double(kMaxParticles))) throw InputError("n", "must be in [1, 2^31 - 1]");
    const TimeOptimalSizes t = time_optimal_sizes(*dist, p, calibrated_time_model(p.d, "cost").coef, o.n);
    choice.sizes = t.sizes;
    choice.levels = static_cast<int>(t.sizes.size());
    choice.model = evaluate_model(*dist, p, t.sizes);
    seconds = t.seconds;
  }
  std::vector<double> sizes;  // in units of r_min
  for (double s : choice.sizes) sizes.push_back(s / dist->r_min());
  const bool excluded = parse_placement(o.placement, "placement") == Placement::excluded;
  // The paper's model (random centres) chooses the sizes; with --placement
  // excluded the excluded-volume model is evaluated for the same sizes.
  if (o.excluded_sizes && !excluded) throw InputError("excluded-sizes", "needs --placement excluded");
  ModelResult m = excluded ? evaluate_excluded_model_reported(*dist, p, choice.sizes) : choice.model;
  const double T_excluded_paper_sizes = m.T_over_N;
  int evaluations = 0;
  if (o.excluded_sizes) {  // refine the paper's sizes under the excluded-volume model
    const ExcludedSizes r = refine_sizes_excluded_reported(*dist, p, choice.sizes);
    m = r.model;
    evaluations = r.evaluations;
    sizes.clear();
    for (double s : r.sizes) sizes.push_back(s / dist->r_min());
  }
  if (o.json) {
    nlohmann::json j;
    j["levels"] = choice.levels;
    j["sizes"] = sizes;
    j["T_over_N"] = m.T_over_N;
    j["T_cd_over_N"] = m.T_cd_over_N;
    j["T_ca_over_N"] = m.T_ca_over_N;
    if (excluded) j["T_over_N_random"] = choice.model.T_over_N;
    if (seconds) {
      j["predicted_seconds_build"] = seconds->build;
      j["predicted_seconds_query"] = seconds->query;
      j["n"] = o.n;
    }
    if (o.excluded_sizes) {
      j["T_over_N_excluded_paper_sizes"] = T_excluded_paper_sizes;
      j["excluded_size_evaluations"] = evaluations;
    }
    j["T_cd_per_level"] = m.T_cd;
    j["P"] = m.P;
    j["m"] = m.m;
    j["params"] = {{"d", p.d}, {"nu", p.nu}, {"K", p.K}, {"search", to_string(p.search)},
                   {"cells", to_string(method)}, {"q", o.q}, {"omega", dist->omega()},
                   {"dist", o.radii_file.empty() ? o.dist : "empirical"},
                   {"levels_searched", o.levels == 0}, {"placement", o.placement}};
    if (file) j["params"]["nu_source"] = in.nu_from_box ? "box" : "given";
    if (o.radii_file.empty() && o.dist == "powerlaw") j["params"]["alpha"] = o.alpha;
    if (o.radii_file.empty() && o.dist == "lognormal") j["params"]["sigma"] = o.sigma;
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::printf("levels L = %d (%s)\nT/N = %.6f  (T_cd/N = %.6f, T_ca/N = %.6f, K = %g)%s\n", choice.levels,
              o.levels == 0 ? "best L*" : "given", m.T_over_N, m.T_cd_over_N, m.T_ca_over_N, p.K,
              excluded ? "  excluded-volume model" : "");
  if (seconds)
    std::printf("sizes minimise this machine's predicted seconds for N = %g: build %.4g s + query %.4g s\n", o.n,
                seconds->build, seconds->query);
  if (excluded && !o.excluded_sizes) std::printf("random-centre model for the same sizes: T/N = %.6f\n", choice.model.T_over_N);
  if (o.excluded_sizes)
    std::printf("sizes refined under the excluded-volume model (%d evaluations); with the paper's sizes T/N = %.6f\n",
                evaluations, T_excluded_paper_sizes);
  std::printf("%5s %14s %12s %12s\n", "h", "s_h/r_min", "P_h", "m_h");
  for (int h = 0; h < choice.levels; ++h)
    std::printf("%5d %14.6g %12.6g %12.6g\n", h + 1, sizes[h], m.P[h], m.m[h]);
}

}  // namespace

void register_model_commands(CLI::App& app) {
  auto o = std::make_shared<ModelOptions>();
  auto* sub = app.add_subcommand("model", "Analytic cost T/N and cell sizes (paper Sects. 3-5)");
  auto* d_opt = sub->add_option("--d", o->d, "dimension, 2 or 3 (with --radii: the file's when it has one)")->capture_default_str();
  auto* nu_opt = sub->add_option("--nu", o->nu, "packing fraction, > 0 (with --radii: from the file's box, or required)")
                     ->capture_default_str();
  sub->add_option("--alpha", o->alpha, "power-law exponent of f(r) = C r^alpha")->capture_default_str();
  sub->add_option("--omega", o->omega, "r_max / r_min, >= 1")->capture_default_str();
  sub->add_option("--K", o->K, kKHelp)->capture_default_str();
  sub->add_option("--search", o->search, "topdown | bottomup")->capture_default_str();
  sub->add_option("--cells", o->cells, "linear | exponential | constant | optimal")->capture_default_str();
  auto* lv = sub->add_option("--levels", o->levels, "number of levels L >= 1 (default: search the best L*)");
  sub->add_option("--q", o->q, "constant method: m_{h+1} / m_h, > 0")->capture_default_str();
  sub->add_option("--dist", o->dist, "powerlaw | lognormal (centred in log r on [1, omega])")
      ->capture_default_str();
  sub->add_option("--sigma", o->sigma, "log-normal: standard deviation of ln r, > 0")->capture_default_str();
  sub->add_option("--radii", o->radii_file,
                  "use the radii of FILE instead (any particle file: docs/PARTICLE_FILES.md)");
  sub->add_option("--placement", o->placement,
                  "random (the paper's model) | excluded (hard-sphere packing: Percus-Yevick pair structure; 2D: omega <= 50)")
      ->capture_default_str();
  sub->add_flag("--excluded-sizes", o->excluded_sizes,
               "with --placement excluded: refine the sizes to minimise the excluded-volume model (slow at omega >= 50)");
  sub->add_option("--cost", o->cost,
                  "what the optimal sizes minimise: count (the paper's T) or time (this machine's predicted seconds "
                  "of build + query, from `hgrid calibrate`)")
      ->capture_default_str();
  sub->add_option("--n", o->n, "with --cost time: number of particles")->capture_default_str();
  sub->add_flag("--json", o->json, "print JSON: levels, sizes (units of r_min), T_over_N, ...");
  sub->callback([o, lv, d_opt, nu_opt] {
    if (lv->count() > 0 && o->levels < 1)
      throw InputError("levels", "must be >= 1 (got " + std::to_string(o->levels) + ")");
    o->d_given = d_opt->count() > 0;
    o->nu_given = nu_opt->count() > 0;
    run_model(*o);
  });

  auto f = std::make_shared<std::string>("results/model");
  auto only = std::make_shared<std::string>();
  auto* figs = app.add_subcommand("modelfigs", "Write the data of the paper's Figs. 2-10 (and 13) as CSV");
  figs->add_option("--out", *f, "output directory")->capture_default_str();
  figs->add_option("--only", *only, "comma-separated figure numbers, e.g. 4,9 (default: all)");
  auto time_model = std::make_shared<std::string>();
  figs->add_option("--time-model", *time_model,
                   "a calibration file (e.g. results/calibration.json) whose 3D time model adds the time-optimal "
                   "sizes to Fig. 13");
  figs->callback([f, only, time_model] {
    std::optional<TimeCoefficients> time;
    if (!time_model->empty()) {
      const Calibration c = load_calibration(*time_model);
      if (!c.time_model(3))
        throw InputError("time-model", "'" + *time_model + "' has no 3D time model (run `hgrid calibrate`)");
      time = c.time_model(3)->coef;
    }
    std::filesystem::create_directories(*f);
    write_model_figures([&](const std::string& name, const std::string& csv) { write_text_atomically(*f + "/" + name, csv); },
                        *only, std::cerr, time);
  });
}

}  // namespace hgrid::cli
