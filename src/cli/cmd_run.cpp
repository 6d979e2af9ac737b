// hgrid run: one scene file -> results/<name>.h5 and .csv.
#include <iostream>
#include <memory>
#include <thread>

#include "common.hpp"
#include "hgridlab/scenes/dpm_scene.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/scenes/runner.hpp"
#include "hgridlab/mpi/comm.hpp"
#include "hgridlab/mpi/sweep.hpp"

namespace hgrid::cli {
namespace {

struct RunArgs {
  std::string scene, scale = "default";
  RunOptions opt;
  bool json = false;
};

void run(const RunArgs& a) {
  if (a.opt.jobs < 1) throw InputError("jobs", "must be >= 1");
  const int ranks = mpi::size();
  if (scene_kind(a.scene) == "dpm") {
    // One simulation, not a sweep of points: nothing to spread over ranks.
    if (ranks > 1) throw InputError("kind", "a DPM scene (kind = \"dpm\") runs on one process: run it without mpirun");
    dpm::run_dpm_scene(a.scene, a.scale, a.opt, a.json);
    return;
  }
  const Scene scene = load_scene(a.scene, a.scale);
  const bool lead = mpi::rank() == 0;  // under MPI, rank 0 alone reports
  if (lead)
    std::cerr << "hgrid run: scene " << scene.name << " (" << a.scale << " scale): " << scene.points.size()
              << " points, " << a.opt.jobs << " job(s)"
              << (ranks > 1 ? " on each of " + std::to_string(ranks) + " ranks" : "") << "\n";
  const auto results = mpi::run_scene_on_ranks(scene, a.opt);
  if (!lead) return;
  std::cerr << "hgrid run: wrote " << result_stem(scene, a.opt) << ".h5 and .csv\n";
  if (!a.json) return;
  std::cout << results_json(scene, results, a.opt) << "\n";
}

}  // namespace

void register_run_commands(CLI::App& app) {
  auto a = std::make_shared<RunArgs>();
  auto* sub = app.add_subcommand(
      "run",
      "run a scene file (experiments/*.toml): packings, counts, model, results. Under mpirun or srun the points "
      "are spread over the ranks (whole packings per rank) and rank 0 writes the same files; a DPM scene is "
      "refused there (it runs on one process)");
  sub->add_option("SCENE", a->scene, "scene file (TOML)")->required();
  sub->add_option("--scale", a->scale, "smoke|default|paper")->default_val("default");
  sub->add_option("--jobs", a->opt.jobs, "points measured in parallel (on each rank under MPI)")->default_val(1);
  sub->add_option("--results", a->opt.results_dir, "directory of the result files")->default_val("results");
  sub->add_option("--packings", a->opt.packing_dir, "packing cache directory")->default_val("results/packings");
  sub->add_flag("--json", a->json, "print a JSON summary of every point on stdout");
  sub->callback([a] { run(*a); });
}

}  // namespace hgrid::cli
