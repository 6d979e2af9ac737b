// Particles as read from a file: the radii always, the centres and the box
// when the file has them. Reads HDF5 packings, CSV or whitespace-separated
// text with named columns (or the plain "x y [z] r" layout), LAMMPS data files
// (atom_style sphere) and LAMMPS dump files; the format is found from the
// content. `hgrid recommend` needs the radii only; a Packing (to_packing)
// needs the centres and the box too.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/packing/packing.hpp"

namespace hgrid {

enum class ParticleFormat { hdf5, table, lammps_data, lammps_dump, mercury_data, mercury_restart };
const char* to_string(ParticleFormat f);

/// What every reader says when a file matches no format.
inline constexpr const char* kParticleFormats =
    "HDF5 packing (.h5), CSV or whitespace text with columns x y [z] and r|radius or d|diameter, a LAMMPS data "
    "file (Atoms # sphere), a LAMMPS dump (ITEM: ATOMS ... x y z radius|diameter), or a MercuryDPM .data or "
    ".restart file";

struct ParticleSet {
  ParticleFormat format = ParticleFormat::table;
  int d = 0;                          // 2 or 3; 0: not known (a list of radii only)
  std::vector<double> radii;          // > 0 and finite, in the file's length unit
  std::vector<double> positions;      // N x d (origin moved to the box's lower corner), or empty
  std::optional<std::array<double, 3>> box;  // side lengths (first d used), when the file has a box
  std::array<double, 3> tilt{};       // a tilted (triclinic) box's xy xz yz (LAMMPS; grid/tilted_box.hpp), else 0
  std::optional<Boundary> boundary;   // when the file says (`# boundary`, dump flags, HDF5)
  bool mixed_boundary = false;        // periodic and non-periodic axes (a LAMMPS dump, a MercuryDPM .restart)
  std::array<bool, 3> periodic_axes{};  // per axis, where the file says so per axis (LAMMPS dumps, .restart files)
  std::size_t frame = 0, frames = 1;  // the snapshot read, of how many the file holds (dumps, MercuryDPM .data)
  std::size_t size() const { return radii.size(); }
  bool has_positions() const { return !positions.empty(); }
  /// Periodic per axis: periodic_axes for a mixed boundary, else the boundary's (assumed periodic if none).
  std::array<bool, 3> periodic_per_axis() const {
    if (mixed_boundary) return periodic_axes;
    const bool p = !boundary || *boundary == Boundary::periodic;
    return {p, p, p};
  }
  bool tilted() const { return tilt[0] != 0 || tilt[1] != 0 || tilt[2] != 0; }
  /// Total particle volume over the box's (needs d and a box).
  double packing_fraction() const;
};

/// Reads `path` in whichever supported format its content shows. Throws
/// InputError naming the field (and file:line for text) for malformed input,
/// and one line listing kParticleFormats for a file that matches none.
/// `frame`: the snapshot of a file that holds several (LAMMPS dumps,
/// MercuryDPM .data files): from the first (0-based), or from the end when
/// negative; nothing: the last. Files of one snapshot take 0 or -1.
ParticleSet read_particles(const std::string& path, Isolation isolation = Isolation::none,
                           std::optional<std::int64_t> frame = std::nullopt);

/// True for an HDF5 file: by its ending (.h5, .hdf5, .hdf) or its signature.
bool hdf5_file(const std::string& path);

/// The text formats (table, LAMMPS data, LAMMPS dump) from memory; `name`
/// names the source in messages.
ParticleSet parse_particles(std::string_view text, const std::string& name,
                            std::optional<std::int64_t> frame = std::nullopt);

/// A Packing for the grids: needs d, centres and a box (InputError "box" or
/// "positions" naming `name` otherwise). A file without a boundary gives a
/// periodic box (the README's rule); a mixed one is refused. Validated.
Packing to_packing(ParticleSet s, const std::string& name);

/// What the boundary of a packing made from `s` is and where it comes from:
/// "periodic", "walls", or "periodic (not in the file: assumed)".
std::string boundary_description(const ParticleSet& s);
/// The same for a packing read by read_packing or to_packing, which mark an
/// assumed boundary with the attribute kBoundarySourceAttr.
std::string boundary_description(const Packing& p);
inline constexpr const char* kBoundarySourceAttr = "boundary_source";
inline constexpr const char* kBoundaryAssumed = "assumed: not in the file";

/// --d with a particle file: the dimension the file must have; InputError
/// naming d when the file's (2D when all its z are equal) differs.
void check_file_dimension(int file_d, std::optional<int> d, const std::string& file);

/// d and nu for the particles `s` read from `file`: the options when given,
/// else the file's (its columns, its box); an InputError naming d or nu, and
/// the option to give, when neither has it.
struct FileInputs {
  int d = 3;
  double nu = 0;
  bool nu_from_box = false;
};
FileInputs file_inputs(const ParticleSet& s, const std::string& file, std::optional<int> d, std::optional<double> nu);

}  // namespace hgrid
