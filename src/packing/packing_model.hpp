// The cost models evaluated for one packing: its own radii, packing
// fraction, boundary and the cell sizes a grid actually used.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/excluded.hpp"
#include "hgridlab/model/model.hpp"
#include "hgridlab/packing/packing.hpp"

namespace hgrid {

struct PackingModels {
  ModelResult random;                   // the paper's model (random centres)
  std::optional<ModelResult> excluded;  // the excluded-volume model, where it applies
  std::string excluded_skipped;         // otherwise: why not
};

/// Both models for the packing's radii (an empirical distribution) and
/// packing fraction, for the sizes used (e.g. HGrid::sizes()); with
/// with_excluded = false only the paper's (the other is seconds at omega = 100
/// in 3D, up to a minute or two in 2D); progress: report a long 2D solution on
/// stderr; wall_pairs: the excluded-volume model's pairs near a wall (walls only).
PackingModels model_for_packing(const Packing& p, const std::vector<double>& sizes, Search search, double K,
                                bool with_excluded = true, bool progress = false,
                                WallPairs wall_pairs = WallPairs::depleted_layer);

/// evaluate_excluded_model with, for discs (seconds to minutes), its
/// iterations on stderr when `progress` (Progress: percentage of the
/// iteration budget, ETA).
ModelResult evaluate_excluded_model_reported(const Distribution& dist, const ModelParams& p,
                                             const std::vector<double>& sizes,
                                             const std::optional<WallBox>& walls = std::nullopt, bool progress = true,
                                             WallPairs wall_pairs = WallPairs::depleted_layer);

}  // namespace hgrid
