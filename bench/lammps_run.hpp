// Running LAMMPS (`lmp` on PATH) on an exported script and reading its log.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

namespace hgrid {

struct LammpsResult {
  bool ok = false;
  std::string error;         // the log's ERROR line when LAMMPS stopped
  double neigh_seconds = 0;  // "Neigh" row of the timing breakdown (average over tasks)
  double neigh_max_seconds = 0;  // its maximum over tasks (the wall time of the stage; = average on 1 task)
  double comm_seconds = 0;   // "Comm" row (ghost atoms, rebuilt with every list)
  std::uint64_t builds = 0;  // "Neighbor list builds"
  std::uint64_t pairs = 0;   // "Total # of neighbors" (half list: each pair once)
  double seconds_per_build() const { return builds ? neigh_seconds / static_cast<double>(builds) : 0.0; }
  double max_seconds_per_build() const { return builds ? neigh_max_seconds / static_cast<double>(builds) : 0.0; }
};

/// Parses a LAMMPS log (text). ok is false if no timing breakdown was found.
LammpsResult parse_lammps_log(const std::string& log);

/// The LAMMPS executable: $HGRID_LMP if set, else `lmp` if on PATH; nullopt otherwise.
std::optional<std::string> find_lammps();

/// Runs `lmp -in script` in dir (log to dir/log.<script>), returns the parsed log.
/// With ranks > 1, as `mpirun -np ranks --oversubscribe` (and
/// --allow-run-as-root as root); mpirun is $HGRID_MPIRUN if set.
LammpsResult run_lammps(const std::string& lmp, const std::string& dir, const std::string& script, int ranks = 1);

}  // namespace hgrid
