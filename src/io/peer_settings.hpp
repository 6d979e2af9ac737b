// Cell sizes as settings to paste into other codes: LAMMPS (`neighbor multi`
// with size collections) and MercuryDPM (its HGrid with user-defined cell
// sizes). The sizes are the HGrid's cell sizes s_1..s_L in the particles'
// unit; level h holds the particles of diameter in (s_{h-1}, s_h].
#pragma once
#include <string>
#include <vector>

#include "hgridlab/grid/params.hpp"

namespace hgrid {

/// Significant digits of pasted sizes.
inline constexpr int kPasteDigits = 6;

/// Each size rounded up to kPasteDigits significant digits (a class bound or
/// a top cell still holds its largest particle); the exact sizes when
/// rounding would merge two of them.
std::vector<double> rounded_up_sizes(const std::vector<double>& sizes);

/// The shortest text that reads back as v ("0.25", "1e-05").
std::string shortest_number(double v);

/// LAMMPS input lines: `neighbor <skin> multi`, `neigh_modify
/// collection/interval L s_1 ... s_L` (LAMMPS puts a particle in the first
/// collection whose bound is >= its cutoff, for granular pair styles its
/// diameter) and `comm_modify mode multi reduce/multi`.
std::vector<std::string> lammps_settings(const std::vector<double>& sizes, double skin);

/// MercuryDPM lines: setHGridMethod, setHGridDistribution(USER),
/// setHGridMaxLevels(L) in the driver's setup, and the override of
/// userHGridCellSize(level) that returns the sizes (in MercuryDPM, cell sizes
/// are in the same length unit as the radii).
std::vector<std::string> mercurydpm_settings(const std::vector<double>& sizes, Search search);

}  // namespace hgrid
