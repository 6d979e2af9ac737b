// What a contact list measured over a run at one skin, as the skin model
// (advice/skin_model.hpp) takes it, and a pass of a list over a recorded
// trajectory: what the skin benchmarks share.
#pragma once
#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "hgridlab/advice/skin_model.hpp"
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

/// From a list's stats after a run of n particles at `skin` that handed over
/// `contacts` contacts in all.
inline SkinMeasurement skin_measurement(double skin, const ContactListStats& l, std::uint64_t contacts, double n) {
  const double builds = static_cast<double>(std::max<std::uint64_t>(1, l.builds)), steps = static_cast<double>(l.steps);
  SkinMeasurement m;
  m.skin = skin;
  m.steps_per_build = steps / builds;
  m.contacts_per_n = static_cast<double>(contacts) / steps / n;
  m.candidates_per_n = static_cast<double>(l.candidates_tested) / steps / n;
  m.seconds_grid = l.seconds_grid / builds;
  m.seconds_store = (l.seconds_build - l.seconds_grid) / builds;
  m.seconds_test = l.seconds_test / steps;
  m.seconds_check = l.seconds_check / steps;
  return m;
}

}  // namespace hgrid::bench
