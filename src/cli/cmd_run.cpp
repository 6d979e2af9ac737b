// hgrid run: scene files -> results/<name>.h5 and .csv each.
#include <iostream>
#include <memory>
#include <thread>
#include <vector>

#include "common.hpp"
#include "hgridlab/scenes/dpm_scene.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/scenes/runner.hpp"
#include "hgridlab/mpi/comm.hpp"
#include "hgridlab/mpi/sweep.hpp"

namespace hgrid::cli {
namespace {

struct RunArgs {
  std::vector<std::string> scenes;
  std::string scale = "default";
  RunOptions opt;
  bool json = false;
};

void run(const RunArgs& a) {
  if (a.opt.jobs < 1) throw InputError("jobs", "must be >= 1");
  const int ranks = mpi::size();
  const bool lead = mpi::rank() == 0;  // under MPI, rank 0 alone reports
  if (a.scenes.size() == 1 && scene_kind(a.scenes[0]) == "dpm") {
    // One simulation, not a sweep of points: nothing to spread over ranks.
    if (ranks > 1) throw InputError("kind", "a DPM scene (kind = \"dpm\") runs on one process: run it without mpirun");
    dpm::run_dpm_scene(a.scenes[0], a.scale, a.opt, a.json);
    return;
  }
  std::vector<Scene> scenes;
  for (const auto& file : a.scenes) {
    if (scene_kind(file) == "dpm") throw InputError("SCENE", "a DPM scene runs alone (" + file + ")");
    scenes.push_back(load_scene(file, a.scale));
    if (lead)
      std::cerr << "hgrid run: scene " << scenes.back().name << " (" << a.scale << " scale): "
                << scenes.back().points.size() << " points, " << a.opt.jobs << " job(s)"
                << (ranks > 1 ? " on each of " + std::to_string(ranks) + " ranks" : "") << "\n";
  }
  // Under MPI one scene after the other, each over the ranks; else one pool.
  std::vector<std::vector<PointResult>> results;
  if (ranks > 1 || scenes.size() == 1)
    for (const Scene& s : scenes) results.push_back(mpi::run_scene_on_ranks(s, a.opt));
  else
    results = run_scenes(scenes, a.opt);
  if (!lead) return;
  for (const Scene& s : scenes) std::cerr << "hgrid run: wrote " << result_stem(s, a.opt) << ".h5 and .csv\n";
  if (!a.json) return;
  if (scenes.size() == 1) {
    std::cout << results_json(scenes[0], results[0], a.opt) << "\n";
    return;
  }
  std::cout << "[\n";
  for (std::size_t k = 0; k < scenes.size(); ++k)
    std::cout << results_json(scenes[k], results[k], a.opt) << (k + 1 < scenes.size() ? ",\n" : "\n");
  std::cout << "]\n";
}

}  // namespace

void register_run_commands(CLI::App& app) {
  auto a = std::make_shared<RunArgs>();
  auto* sub = app.add_subcommand(
      "run",
      "run scene files (experiments/*.toml): packings, counts, model, results. Several scenes share one pool of "
      "--jobs workers (a packing two scenes share is made once) and write the files each would alone. Under mpirun "
      "or srun the points are spread over the ranks (whole packings per rank), one scene after the other, and rank 0 "
      "writes the same files; a DPM scene runs alone, and not there (it runs on one process)");
  sub->add_option("SCENE", a->scenes, "scene files (TOML)")->required();
  sub->add_option("--scale", a->scale, "smoke|default|paper")->default_val("default");
  sub->add_option("--jobs", a->opt.jobs, "points measured in parallel (on each rank under MPI)")->default_val(1);
  sub->add_option("--results", a->opt.results_dir, "directory of the result files")->default_val("results");
  sub->add_option("--packings", a->opt.packing_dir, "packing cache directory")->default_val("results/packings");
  sub->add_flag("--json", a->json, "print a JSON summary of every point on stdout");
  sub->callback([a] { run(*a); });
}

}  // namespace hgrid::cli
