// Scene files (TOML): one experiment, the packings it needs and what it records.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/packing/generate.hpp"
#include "hgridlab/grid/params.hpp"

namespace hgrid {

/// How the grid of every point is set up.
struct SceneGrid {
  CellMethod cells = CellMethod::optimal;  // by the cost model, for the packing's own radii
  std::optional<int> levels;      // fixed L, or the method's best L*
  double q = 1.0;                 // ratio of particles per cell (constant method)
  double K = 0.2;                 // cell access time / overlap test time
  std::vector<Search> searches{Search::top_down};
};

/// What a scene records beyond the counts; nothing else is computed.
struct SceneRecord {
  bool model = true;       // evaluate the cost model for the sizes used
  bool occupancy = false;  // share of lowest-level cells holding >= 2 particles
};

/// One unit of work: a packing and a search direction.
struct ScenePoint {
  PackingSpec packing;
  Search search = Search::top_down;
};

struct Scene {
  std::string name;
  std::string description;
  std::string scale;
  std::string source;  // the TOML text, stored with the results
  SceneGrid grid;
  SceneRecord record;
  std::vector<ScenePoint> points;  // the cartesian product of the packing lists
};

/// Point i of a scene for messages: "point 3 of 16 (d=3 n=20000 nu=0.6
/// alpha=-3 omega=100 walls random seed=7, bottomup)".
std::string describe_point(const Scene& scene, std::size_t i);

/// The scene's top-level `kind`: "contact" (default: one contact search per
/// point, load_scene) or "dpm" (a discrete-element run, dpm/dpm_scene.hpp).
std::string scene_kind(const std::string& path);

/// Reads a scene for one scale ("smoke", "default", "paper"): the base
/// packings table with the keys of the table scale.NAME.packings replacing it. Unknown
/// keys and out-of-range values throw InputError naming the key.
Scene load_scene(const std::string& path, const std::string& scale);

/// The same from the scene's text (`name` names it in messages).
Scene load_scene_text(const std::string& text, const std::string& scale, const std::string& name);

}  // namespace hgrid
