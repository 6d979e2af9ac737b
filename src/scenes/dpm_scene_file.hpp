// A DPM scene file (kind = "dpm"): initial state, contact law, effects, run
// length and the two grids compared, with scale overrides.
#pragma once
#include <cstdint>
#include <string>

#include "hgridlab/dpm/config.hpp"
#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/packing/generate.hpp"

namespace hgrid::dpm {

struct DpmScene {
  std::string name, description, scale, source;
  PackingSpec initial;       // [initial]
  double speed = 1.0;        // [initial] speed: std of each initial velocity component
  std::uint64_t velocity_seed = 1;
  DpmConfig config;          // [contact], [effects]; box and sizes come later
  double dt_over_tc = 0.02;  // [contact] dt_over_tc
  std::uint64_t steps = 0;   // [run]
  std::uint64_t sample_every = 100;
  double K = 0.2;            // [grids]
  CellMethod method = CellMethod::optimal;
  double reference_size = 40;  // linked cell: one level of this size (units of r_min)
};

/// Reads and checks a scene at a scale (smoke|default|paper). Every unknown
/// key or bad value throws InputError naming it.
DpmScene load_dpm_scene(const std::string& path, const std::string& scale);

}  // namespace hgrid::dpm
