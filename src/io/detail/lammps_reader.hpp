// LAMMPS particle files: data files of atom_style sphere (the `Atoms # sphere`
// section: id type diameter density x y z [ix iy iz]) and dump files (one
// snapshot, the last unless asked: ITEM: BOX BOUNDS, ITEM: ATOMS with
// x|xu|xs y z and radius|diameter in any order).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "hgridlab/io/particle_file.hpp"

namespace hgrid::detail {

/// True when the text's header (before the first section) has an "N atoms" line.
bool looks_like_lammps_data(std::string_view text);

ParticleSet parse_lammps_data(std::string_view text, const std::string& name);
/// The snapshot `frame` of a dump (from the first, 0-based, or from the end
/// when negative; nothing: the last).
ParticleSet parse_lammps_dump(std::string_view text, const std::string& name, std::optional<std::int64_t> frame);

}  // namespace hgrid::detail
