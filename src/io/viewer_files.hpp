// Particle files for viewers, with each particle's radius, level of insertion
// and cell: extended XYZ (OVITO, ASE) and legacy VTK polydata (ParaView).
// Both written atomically (a temporary name, then renamed).
#pragma once
#include <string>

#include "hgridlab/packing/grid_placement.hpp"
#include "hgridlab/packing/packing.hpp"

namespace hgrid {

/// Extended XYZ: the particle count, a comment line with Lattice (the box),
/// Origin, pbc and Properties=species:S:1:pos:R:3:radius:R:1:level:I:1:cell:I:1,
/// then one line per particle (species "P"; 2D: z = 0 and a unit third
/// lattice vector, pbc F along it).
std::string extended_xyz(const Packing& p, const GridPlacement& g);
void write_extended_xyz(const std::string& path, const Packing& p, const GridPlacement& g);

/// Legacy VTK (ASCII) POLYDATA: the centres as POINTS and VERTICES, and
/// POINT_DATA scalars radius (double), level (int) and cell (double: exact
/// below 2^53).
std::string legacy_vtk(const Packing& p, const GridPlacement& g);
void write_legacy_vtk(const std::string& path, const Packing& p, const GridPlacement& g);

}  // namespace hgrid
