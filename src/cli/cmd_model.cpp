// `hgrid model`: the analytic cost model for one distribution.
#include <filesystem>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "common.hpp"
#include "hgridlab/advice/model_answer.hpp"
#include "hgridlab/io/atomic_file.hpp"
#include "hgridlab/calibration/calibration.hpp"
#include "hgridlab/packing/generate.hpp"
#include "hgridlab/model/figures.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/io/particle_file.hpp"

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
  ModelQuestion q;
  q.params = ModelParams{in.d, in.nu, resolve_K(o.K, "K"), parse_search(o.search)};
  q.cells = parse_cell_method(o.cells);
  if (o.levels > 0) q.levels = o.levels;
  q.q = o.q;
  const Placement placement = parse_placement(o.placement, "placement");
  if (placement == Placement::bed)
    throw InputError("placement", "must be 'random' or 'excluded' for the model (a bed is not homogeneous: `hgrid recommend` on its file)");
  q.excluded = placement == Placement::excluded;
  q.excluded_sizes = o.excluded_sizes;
  q.cost = parse_cost(o.cost);
  q.n = o.n;
  const auto dist = make_distribution(o, file);
  const ModelAnswer a = answer_model(*dist, q);
  if (!o.json) {
    std::cout << model_answer_text(a, q);
    return;
  }
  nlohmann::json j = nlohmann::json::parse(model_answer_json(a, q));
  const ModelParams& p = q.params;
  j["params"] = {{"d", p.d}, {"nu", p.nu}, {"K", p.K}, {"search", to_string(p.search)},
                 {"cells", to_string(q.cells)}, {"q", o.q}, {"omega", dist->omega()},
                 {"dist", o.radii_file.empty() ? o.dist : "empirical"},
                 {"levels_searched", o.levels == 0}, {"placement", o.placement}};
  if (file) j["params"]["nu_source"] = in.nu_from_box ? "box" : "given";
  if (o.radii_file.empty() && o.dist == "powerlaw") j["params"]["alpha"] = o.alpha;
  if (o.radii_file.empty() && o.dist == "lognormal") j["params"]["sigma"] = o.sigma;
  std::cout << j.dump(2) << "\n";
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
}

}  // namespace hgrid::cli
