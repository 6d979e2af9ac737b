// Scene sweeps over MPI ranks (`mpirun -np P hgrid run SCENE`): the points of
// a scene spread over the ranks, the results written by rank 0 exactly as a
// run without MPI writes them.
#pragma once
#include <string>
#include <vector>

#include "hgridlab/scenes/runner.hpp"

namespace hgrid::mpi {

/// The one scene runner (scenes/run_scene.hpp) with the ranks of the MPI run
/// as its executor: every rank calls it; rank 0 reads the journals, each rank
/// measures its groups (opt.jobs at a time) and journals them in its own
/// file, rank 0 gathers and writes. A failure on any rank fails every rank
/// (mpi::collective). Returns the results on rank 0 (nothing elsewhere).
std::vector<PointResult> run_scene_on_ranks(const Scene& scene, const RunOptions& opt);

/// What `hgrid run` does with scene files (scenes/run_scene.hpp's
/// run_scene_files) with the ranks of the MPI run as its executor; without
/// MPI, or under mpirun with one rank, that is this process alone.
std::string run_scene_files(const std::vector<std::string>& files, const std::string& scale, const RunOptions& opt,
                            bool json);

}  // namespace hgrid::mpi
