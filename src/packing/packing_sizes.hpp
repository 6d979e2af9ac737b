// Cell sizes for a packing, chosen by the cost model for its own radii.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/model/excluded.hpp"
#include "hgridlab/model/time_model.hpp"
#include "hgridlab/packing/packing.hpp"
#include "hgridlab/grid/params.hpp"

namespace hgrid {

struct SizeRequest {
  CellMethod method = CellMethod::optimal;
  std::optional<int> levels;
  double q = 1.0;
  /// optimal only: refine the sizes under the excluded-volume model.
  bool excluded_model = false;
  /// optimal only: minimise the time model's predicted seconds of one build
  /// + query with these coefficients (this machine's, from `hgrid
  /// calibrate`) instead of T (time_optimal_sizes).
  std::optional<TimeCoefficients> time_model;
};

/// Sizes from the cost model for the packing's radii (an empirical
/// distribution) and its packing fraction, ready for GridParams: strictly
/// increasing (collapsed levels, and levels fitted to the same cells, merged)
/// and the last holding the largest particle.
std::vector<double> model_sizes(const Packing& p, const SizeRequest& r, Search search, double K);

/// In a periodic box each level's cells are fitted to the box (an integer
/// number per axis, HGrid's layout): levels fitted to the same cells are one
/// level (the upper one holds nothing, and the sizes the grid reports would
/// repeat), so they are merged, keeping the upper size. Walls: unchanged.
std::vector<double> merge_fitted_levels(std::vector<double> sizes, const Packing& p);

/// refine_sizes_excluded with its progress (evaluations, best T/N, ETA) on stderr.
ExcludedSizes refine_sizes_excluded_reported(const Distribution& dist, const ModelParams& p,
                                             const std::vector<double>& sizes);

}  // namespace hgrid
