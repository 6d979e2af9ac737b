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

/// How model_for_packing evaluates the excluded-volume model.
struct PackingModelOptions {
  bool excluded = true;   // false: only the paper's model (the other takes seconds at omega = 100 in 3D, more in 2D)
  bool progress = false;  // report a long 2D solution on stderr
  WallPairs wall_pairs = WallPairs::depleted_layer;  // walls only: its pairs near a wall
  double disc_work_budget = 0;  // 2D: ExcludedOptions::disc_work_budget (0: none)
};

/// Both models for the packing's radii (an empirical distribution) and
/// packing fraction, for the sizes used (e.g. HGrid::sizes()). Where the
/// excluded-volume model does not apply or is refused, excluded_skipped says
/// why (the refusal's message).
PackingModels model_for_packing(const Packing& p, const std::vector<double>& sizes, Search search, double K,
                                const PackingModelOptions& opt = {});

/// evaluate_excluded_model with, for discs (seconds to minutes), its
/// iterations on stderr when `progress` (Progress: percentage of the
/// iteration budget, ETA).
ModelResult evaluate_excluded_model_reported(const Distribution& dist, const ModelParams& p,
                                             const std::vector<double>& sizes,
                                             const std::optional<WallBox>& walls = std::nullopt, bool progress = true,
                                             WallPairs wall_pairs = WallPairs::depleted_layer,
                                             double disc_work_budget = 0);

}  // namespace hgrid
