// MercuryDPM's .data files (the XBalls format its DPMBase writes; notes and
// citations in docs/record/MERCURYDPM_FILES.md): snapshots one after another, each
// a header "N t xmin ymin xmax ymax" (2D) or "N t xmin ymin zmin xmax ymax
// zmax" (3D) and N particle lines "x y vx vy r angle omega info" (8 values)
// or "x y z vx vy vz r a1 a2 a3 wx wy wz info" (14 values).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "hgridlab/io/particle_file.hpp"

namespace hgrid::detail {

/// True when the first non-blank line is a MercuryDPM header (6 or 8
/// numbers, the first a whole number N) and the next one a particle line of
/// 8 or 14 numbers to match (or, when N = 0, another header).
bool looks_like_mercury_data(std::string_view text);

/// The snapshot `frame` (from the first, 0-based, or from the end when
/// negative; nothing: the last). Its domain is the box; the file does not
/// say the boundary.
ParticleSet parse_mercury_data(std::string_view text, const std::string& name, std::optional<std::int64_t> frame);

/// A MercuryDPM .restart file (mercury_restart.cpp): its first line names
/// MercuryDPM (or restart_version).
bool looks_like_mercury_restart(std::string_view text);

/// Its particles (one snapshot), dimension, box and boundary: periodic where
/// Periodic, Lees-Edwards or shear-box boundaries say (a shift across y is
/// the tilt xy), else walled between its walls or its domain.
ParticleSet parse_mercury_restart(std::string_view text, const std::string& name);

}  // namespace hgrid::detail
