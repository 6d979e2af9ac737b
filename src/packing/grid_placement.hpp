// Where each particle of a packing sits in an HGrid: its level of insertion
// and its cell, for files that show the grid (io/viewer_files.hpp).
#pragma once
#include <cstdint>
#include <vector>

#include "hgridlab/grid/params.hpp"
#include "hgridlab/packing/packing.hpp"

namespace hgrid {

struct GridPlacement {
  std::vector<double> sizes;          // the cell sizes the grid uses (periodic boxes fit them to the box)
  std::vector<int> level;             // per particle: level of insertion, 1-based
  std::vector<std::uint64_t> cell;    // per particle: linear cell index in its level (last axis fastest)
};

/// Builds the grid of `params` on p and reads every particle's placement.
/// Throws InputError for sizes the grid refuses.
GridPlacement place_in_grid(const Packing& p, const GridParams& params);

}  // namespace hgrid
