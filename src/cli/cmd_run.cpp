// hgrid run: scene files -> results/<name>.h5 and .csv each.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "common.hpp"
#include "hgridlab/mpi/sweep.hpp"

namespace hgrid::cli {
namespace {

struct RunArgs {
  std::vector<std::string> scenes;
  std::string scale = "default";
  RunOptions opt;
  bool json = false;
};

void run(const RunArgs& a) { std::cout << mpi::run_scene_files(a.scenes, a.scale, a.opt, a.json); }

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
