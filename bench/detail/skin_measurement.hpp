// What the skin benchmarks share: the sizes their baseline is scanned over
// and a pass of a contact list over a recorded trajectory (its stats give
// the skin model's measurement: advice/skin_tuner.hpp, skin_measurement).
#pragma once
#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "hgridlab/contacts/contact_list.hpp"
#include "hgridlab/model/cell_sizes.hpp"

namespace hgrid::bench {

/// The sizes a benchmark's baseline (the grid rebuilt every step) is scanned
/// over: the paper's optimal Bottom-Up sizes (K = 0.2) for nu = 0.1 ... 0.7
/// ("nu=0.1" ...) and the linked cell ("linked cell"), for radii `dist` in 3D.
inline std::map<std::string, std::vector<double>> scanned_sizes(const Distribution& dist) {
  std::map<std::string, std::vector<double>> sized;
  for (double nu : {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7})
    sized["nu=" + std::to_string(nu).substr(0, 3)] = sizes_for_grid(
        choose_cell_sizes(dist, ModelParams{3, nu, 0.2, Search::bottom_up}, CellMethod::optimal).sizes, 2 * dist.r_max());
  sized["linked cell"] = {2 * dist.r_max()};
  return sized;
}

/// A contact list's pass over a recorded trajectory: its seconds per step,
/// its stats and the contacts it handed over in all.
struct ListRun {
  double seconds_per_step = 1e300;
  ContactListStats stats;
  std::uint64_t contacts = 0;
};

}  // namespace hgrid::bench
