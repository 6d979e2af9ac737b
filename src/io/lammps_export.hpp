// LAMMPS export: a packing as a LAMMPS data file (atom_style sphere)
// and input scripts that time LAMMPS's own neighbour-list builds on it, so
// hgridlab's HGrid can be compared with LAMMPS `neighbor multi` and `bin`.
#pragma once
#include <string>
#include <vector>

#include "hgridlab/packing/packing.hpp"

namespace hgrid {

/// How LAMMPS bins the particles.
enum class LammpsNeighbor { multi, bin };
inline const char* to_string(LammpsNeighbor n) { return n == LammpsNeighbor::multi ? "multi" : "bin"; }

struct LammpsScript {
  LammpsNeighbor neighbor = LammpsNeighbor::multi;
  /// multi only: upper bounds of the size classes (neigh_modify
  /// collection/interval), as particle diameters, increasing; the last must be
  /// >= the largest diameter. Empty: geometric_collections(p, 4, 2 r_min).
  std::vector<double> collections;
  /// Timed neighbour-list builds (`run builds`, one build per step).
  int builds = 10;
  std::string data_file = "data.lmp";
};

/// k class bounds growing geometrically from `smallest` to the largest
/// diameter of p (k = 1: one class of the largest diameter). Throws InputError.
std::vector<double> geometric_collections(const Packing& p, int k, double smallest);

/// "neigh_modify collection/interval k c1 ... ck", each bound the shortest
/// text that reads back as it.
std::string lammps_collection_interval(const std::vector<double>& collections);

/// The data file text: `atom_style sphere` lines `id type diameter density x y z`
/// (one atom type, density 1). Periodic: the box [0, A); walls: [0, A] widened
/// by 1e-9 A at the top (LAMMPS boxes are half open); 2D: z = 0 in a box
/// [-0.5, 0.5] (LAMMPS's 2D convention).
std::string lammps_data(const Packing& p);

/// The input script text: reads the data file, `pair_style gran/hooke` (its
/// neighbour cutoff for a pair is r_i + r_j), zero skin, neighbour list rebuilt
/// every step with motionless particles; the log's "Neigh" time over "Neighbor
/// list builds" is the time per build and "Total # of neighbors" the pair count.
std::string lammps_input(const Packing& p, const LammpsScript& s);

/// Writes dir/data.lmp, dir/in.multi.lmp (collections: s.collections) and
/// dir/in.bin.lmp, each under a temporary name then renamed. Creates dir.
void export_lammps(const std::string& dir, const Packing& p, const LammpsScript& s = {});

}  // namespace hgrid
