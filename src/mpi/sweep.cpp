#include "hgridlab/mpi/sweep.hpp"

#include "hgridlab/mpi/comm.hpp"
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
  RankRun ranks;
  return hgrid::run_scene_files(files, scale, opt, json, ranks);
}

}  // namespace hgrid::mpi
