// A recommendation as JSON text: the keys `hgrid recommend --json` and the
// Python module's recommend() share (docs/RECOMMEND.md lists them).
#pragma once
#include <string>

#include "hgridlab/calibration/k_choice.hpp"
#include "hgridlab/advice/recommend.hpp"

namespace hgrid {

/// Keys: r_min, r_max, omega, K, K_source, calibration_path, K_note, search, levels,
/// sizes, sizes_pasted, fraction_per_level, particles_per_cell, T_over_N,
/// T_cd_over_N, T_ca_over_N, linked_cell_size, linked_cell_T_over_N, speedup,
/// cost (count|time), predicted_seconds_build, predicted_seconds_query,
/// linked_cell_predicted_seconds, speedup_seconds (null unless cost is time),
/// lammps (with `skin`), mercurydpm.
std::string recommendation_json(const Recommendation& r, const KChoice& k, Search search, double skin);

}  // namespace hgrid
