// CSV and whitespace-separated text particle files: named columns in any
// order (x, y[, z] and a radius or a diameter under common names; other
// columns ignored), or no header and the plain layouts r, x y r, x y z r;
// `# box A1 A2 [A3]` and `# boundary periodic|walls` comment lines.
#pragma once
#include <string>
#include <string_view>

#include "hgridlab/io/particle_file.hpp"

namespace hgrid::detail {

ParticleSet parse_table(std::string_view text, const std::string& name);

/// Column roles of a header: index of x, y, z and of the size (-1: absent).
struct Columns {
  int axis[3] = {-1, -1, -1};
  int size = -1;
  bool diameter = false;  // the size column holds diameters
  bool scaled[3] = {false, false, false};  // LAMMPS dumps: xs ys zs (fractions of the box)
  /// 3 (x y z), 2 (x y), 0 (no coordinates); -1 for an incomplete set (z
  /// without x, y without x, ...).
  int dims() const {
    const bool x = axis[0] >= 0, y = axis[1] >= 0, z = axis[2] >= 0;
    return x && y && z ? 3 : x && y ? 2 : !x && !y && !z ? 0 : -1;
  }
  bool any_scaled() const { return scaled[0] || scaled[1] || scaled[2]; }
};

/// The roles of header names (case-insensitive; a unit in brackets, "r [m]",
/// and quotes are ignored); the first column of each role wins, a radius
/// over a diameter, real coordinates over LAMMPS's scaled ones (xs, xsu).
Columns map_columns(const std::vector<std::string>& names);

}  // namespace hgrid::detail
