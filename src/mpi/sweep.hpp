// Scene sweeps over MPI ranks (`mpirun -np P hgrid run SCENE`): the points of
// a scene spread over the ranks, the results written by rank 0 exactly as a
// run without MPI writes them.
#pragma once
#include <vector>

#include "hgridlab/scenes/runner.hpp"

namespace hgrid::mpi {

/// The rank that measures each of `groups` (group_by_packing): greedy, the
/// largest estimated work first to the rank with the least so far. The
/// estimate is n x (points + 1): generating the packing and measuring each
/// point both grow about linearly with n. Ties go to the lower group and
/// rank, so that every rank computes the same owners.
std::vector<int> assign_groups(const Scene& scene, const std::vector<std::vector<std::size_t>>& groups, int ranks);

/// run_scene on every rank of the MPI run; every rank calls it. Rank 0 reads
/// the journals of interrupted runs and tells the ranks what is left; each
/// rank measures its groups (opt.jobs threads each) and journals them in its
/// own file (journal_path(stem, rank)); rank 0 gathers the results, writes
/// the result files and removes the journals. A failure on any rank fails
/// every rank (mpi::collective), the failing point named, and writes no
/// result file. Returns the results on rank 0 (nothing elsewhere); with one
/// rank it is run_scene.
std::vector<PointResult> run_scene_on_ranks(const Scene& scene, const RunOptions& opt);

}  // namespace hgrid::mpi
