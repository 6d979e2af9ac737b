#include "hgridlab/mpi/sweep.hpp"

#include <iostream>

#include "hgridlab/base/error.hpp"
#include "hgridlab/mpi/comm.hpp"
#include "hgridlab/scenes/dpm_scene.hpp"
#include "hgridlab/scenes/run_scene.hpp"

namespace hgrid::mpi {
namespace {

/// The ranks of the MPI run as run_scene's executor.
struct RankRun {
  int rank() const { return mpi::rank(); }
  int size() const { return mpi::size(); }
  template <class F>
  void collective(F&& f) { mpi::collective(std::forward<F>(f)); }
  std::string broadcast(const std::string& s) { return mpi::broadcast(s); }
  std::vector<std::string> gather(const std::string& s) { return mpi::gather(s); }
};

}  // namespace

std::vector<PointResult> run_scene_on_ranks(const Scene& scene, const RunOptions& opt) {
  RankRun ranks;
  return run_scene(scene, opt, ranks);
}

std::string run_scene_files(const std::vector<std::string>& files, const std::string& scale, const RunOptions& opt,
                            bool json) {
  if (opt.jobs < 1) throw InputError("jobs", "must be >= 1");
  const int ranks = mpi::size();
  const bool lead = mpi::rank() == 0;  // under MPI, rank 0 alone reports
  if (files.size() == 1 && scene_kind(files[0]) == "dpm") {
    // One simulation, not a sweep of points: nothing to spread over ranks.
    if (ranks > 1) throw InputError("kind", "a DPM scene (kind = \"dpm\") runs on one process: run it without mpirun");
    return dpm::run_dpm_scene(files[0], scale, opt, json);
  }
  std::vector<Scene> scenes;
  for (const auto& file : files) {
    if (scene_kind(file) == "dpm") throw InputError("SCENE", "a DPM scene runs alone (" + file + ")");
    scenes.push_back(load_scene(file, scale));
    if (lead)
      std::cerr << "hgrid run: scene " << scenes.back().name << " (" << scale << " scale): "
                << scenes.back().points.size() << " points, " << opt.jobs << " job(s)"
                << (ranks > 1 ? " on each of " + std::to_string(ranks) + " ranks" : "") << "\n";
  }
  // Under MPI one scene after the other, each over the ranks; else one pool.
  std::vector<std::vector<PointResult>> results;
  if (ranks > 1 || scenes.size() == 1)
    for (const Scene& s : scenes) results.push_back(run_scene_on_ranks(s, opt));
  else
    results = run_scenes(scenes, opt);
  if (!lead) return "";
  for (const Scene& s : scenes) std::cerr << "hgrid run: wrote " << result_stem(s, opt) << ".h5 and .csv\n";
  if (!json) return "";
  if (scenes.size() == 1) return results_json(scenes[0], results[0], opt) + "\n";
  std::string out = "[\n";
  for (std::size_t k = 0; k < scenes.size(); ++k)
    out += results_json(scenes[k], results[k], opt) + (k + 1 < scenes.size() ? ",\n" : "\n");
  return out + "]\n";
}

}  // namespace hgrid::mpi
