// The decomposed contact search over the ranks of an MPI run: each rank
// reads its part of a packing file, sends every particle to the rank whose
// brick holds its centre, sends and receives the level-aware ghosts
// (domain/decomposition.hpp) and searches its brick with an HGrid; every
// overlapping pair is reported by exactly one rank. Without MPI (or with one
// rank) it is the serial search with the same output.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hgridlab/grid/counters.hpp"
#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/grid/params.hpp"
#include "hgridlab/measure/measurement.hpp"

namespace hgrid::mpi {

/// What one rank did.
struct RankReport {
  int rank = 0;
  std::uint64_t owned = 0;         // particles whose centre is in its brick
  std::uint64_t ghosts = 0;        // copies it received (the level-aware layer)
  std::uint64_t shell_ghosts = 0;  // copies a 2 r_max shell would have sent it
  double seconds_read = 0, seconds_exchange = 0, seconds_build = 0, seconds_query = 0;
  std::uint64_t grid_bytes = 0;     // its HGrid (HGrid::memory_bytes)
  std::uint64_t peak_rss_bytes = 0;  // the process's peak resident memory
};

struct DecomposedRun {
  int d = 3;
  Boundary boundary = Boundary::periodic;
  std::uint64_t n = 0;
  std::array<double, 3> box{};
  double packing_fraction = 0;
  double r_max = 0;
  std::vector<int> bricks;          // bricks per axis
  std::vector<double> sizes;        // cell sizes the grids used
  /// Summed over the ranks, ghosts' searches included; contacts = the
  /// overlapping pairs, each reported once.
  Counters work;
  std::uint64_t ghosts = 0, shell_ghosts = 0;
  /// Volume of a brick's halo: the level-aware layer's (grown by 2 r for a
  /// particle of radius r, averaged over the particles) and the 2 r_max shell's.
  double halo_volume = 0, halo_volume_shell = 0;
  std::vector<double> radii_sample;  // rank 0: at most kRadiiSample radii, evenly over the file (for the model)
  std::vector<RankReport> ranks;     // rank 0: every rank's report, in rank order
};

/// Radii sent to rank 0 for the cost model: every k-th particle of the file.
inline constexpr std::uint64_t kRadiiSample = 1000000;

/// Searches the packing in `file` on every rank of the run (a collective
/// call), with the grid params `g` (g.threads per rank). counted: the
/// counters are counted (hgrid count). pairs_on_root: if not null, every
/// pair (i < j, the file's 0-based particle indices) is gathered there on
/// rank 0, in no particular order.
DecomposedRun decomposed_search(const std::string& file, const GridParams& g, bool counted,
                                std::vector<std::pair<std::uint64_t, std::uint64_t>>* pairs_on_root);

/// The counted decomposed search as a report (`hgrid count --decompose`):
/// the one measurement record (measure/measurement.hpp) for the work of
/// every rank, ghosts' searches included (what decomposing costs), with the
/// serial grid's model for the radii sample; and the run it came from.
/// A collective call; the report is filled on rank 0.
struct DecomposedCount {
  Measurement m;
  DecomposedRun run;
};
DecomposedCount decomposed_count(const std::string& file, const GridParams& g, double K);

/// The report as JSON: the record's fields a decomposed search fills, then
/// the decomposition's (box, bricks, ghosts, halo volumes), each phase's
/// seconds on the slowest rank, memory, and every rank's own report.
std::string decomposed_count_json(const DecomposedCount& c);
/// The report as text: one line of parameters, a row per rank, the totals.
std::string decomposed_count_text(const DecomposedCount& c);

}  // namespace hgrid::mpi
