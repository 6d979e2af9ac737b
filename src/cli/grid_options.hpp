// The options that `hgrid pairs` and `hgrid count` share: the packing
// file, its frame and dimension, and how the grid's cell sizes are given.
#pragma once
#include <optional>
#include <string>

#include "common.hpp"
#include "hgridlab/grid/params.hpp"
#include "hgridlab/model/excluded.hpp"
#include "hgridlab/packing/packing.hpp"
#include "hgridlab/packing/packing_sizes.hpp"

namespace hgrid::cli {

struct GridOptions {
  std::string file;
  std::optional<std::int64_t> frame;
  std::optional<int> d;  // the file's dimension, checked when given
  std::string sizes;
  std::string search = "topdown";
  std::string cost = "count";
  std::string cells;  // a cell-size method, parsed in resolve()
  SizeRequest request;
  int threads = 0;  // 0: all cores (OMP_NUM_THREADS)
  bool decompose = false;  // over the ranks of an MPI run (cmd_decompose.cpp)
  std::string wall_pairs = "layer";  // count: the excluded-volume model's pairs near a wall
  double excluded_budget = kDiscWorkPerSecond;  // count: most multiply-adds of the 2D excluded-volume model
};

void add_grid_options(CLI::App* sub, GridOptions& o);
/// The params of a decomposed search: --sizes only (choosing sizes needs
/// every radius on one rank: `hgrid recommend FILE` prints them).
GridParams decomposed_params(const GridOptions& o);
/// The grid's params for packing p: the sizes given, or chosen by the cost
/// model (--cells, --cost time from this machine's calibration).
GridParams resolve(const GridOptions& o, const Packing& p, double K);
/// The packing of FILE (--frame), refused when --d disagrees with it.
Packing read_grid_packing(const GridOptions& o);

}  // namespace hgrid::cli
