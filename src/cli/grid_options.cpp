#include "grid_options.hpp"

#include <algorithm>
#include <cstdio>

#include "hgridlab/advice/recommend.hpp"
#include "hgridlab/calibration/calibration.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/io/particle_file.hpp"

namespace hgrid::cli {

void add_grid_options(CLI::App* sub, GridOptions& o) {
  sub->add_option("FILE", o.file, "packing file (HDF5, CSV/text, LAMMPS data or dump, MercuryDPM .data or .restart)")->required();
  add_frame_option(sub, o.frame);
  sub->add_option("--d", o.d, "the file's dimension, 2 or 3: refused if the file's differs (default: the file's)");
  auto* sizes = sub->add_option("--sizes", o.sizes, "cell sizes s1,s2,...,sL (increasing, same unit as the radii)");
  auto* cells = sub->add_option("--cells", o.cells,
                                "choose the sizes with the cost model: linear|exponential|constant|optimal");
  sizes->excludes(cells);
  sub->add_option("--levels", o.request.levels, "with --cells: number of levels L (default: the best L*)");
  sub->add_option("--q", o.request.q, "with --cells constant: ratio of particles per cell between levels")
      ->default_val(1.0);
  sub->add_option("--search", o.search, "cross-level search: topdown|bottomup")->default_val("topdown");
  sub->add_option("--cost", o.cost,
                  "with --cells optimal: what the sizes minimise: count (the paper's T = checks + K accesses) or "
                  "time (this machine's predicted seconds of build + query; needs `hgrid calibrate`)")
      ->default_val("count");
  sub->add_flag("--excluded-sizes", o.request.excluded_model,
                "with --cells optimal: refine the sizes under the excluded-volume model (hard-sphere packings; 2D: omega <= 50)");
  add_threads_option(sub, o.threads);
  sub->add_flag("--decompose", o.decompose,
                "under mpirun/srun: split the box into one brick per rank, each searched by its rank with the "
                "ghosts it needs (needs --sizes; without MPI: one rank)");
}

GridParams decomposed_params(const GridOptions& o) {
  if (o.sizes.empty())
    throw InputError("sizes", "--decompose needs --sizes s1,...,sL (`hgrid recommend FILE` prints good ones)");
  if (parse_cost(o.cost) == CostKind::time) throw InputError("cost", "'time' chooses sizes: not with --decompose");
  return GridParams{parse_list(o.sizes, "sizes"), parse_search(o.search), threads_per_rank(check_threads(o.threads))};
}

GridParams resolve(const GridOptions& o, const Packing& p, double K) {
  GridParams g;
  g.search = parse_search(o.search);
  g.threads = check_threads(o.threads);
  if (!o.sizes.empty()) {
    g.sizes = parse_list(o.sizes, "sizes");
  } else if (!o.cells.empty()) {
    SizeRequest r = o.request;
    r.method = parse_cell_method(o.cells);
    if (parse_cost(o.cost) == CostKind::time) r.time_model = calibrated_time_model(p.d, "cost").coef;
    g.sizes = model_sizes(p, r, g.search, K);
    // Optimal sizes for a packing far from homogeneous (a bed under an
    // empty box): the field model's, as `hgrid recommend` gives them.
    if (r.method == CellMethod::optimal && !r.time_model && !r.excluded_model && !r.levels) {
      const std::optional<DensityField> field = density_field_of(p);
      FieldUse look;  // the field's summary first: close to homogeneous (the figures' packings) ends here
      if (field) look.summary = field->summary(3 * 2 * *std::max_element(p.radii.begin(), p.radii.end()));
      if (field && look.far_from_homogeneous()) {
        const Recommendation rec = recommend_for_field(*field, ModelParams{p.d, 0.5, K, g.search});
        g.sizes = merge_fitted_levels(rec.sizes, p);
        std::fprintf(stderr, "cells: the field model's optimal sizes (far from homogeneous: nu %.3g over the box, "
                             "%.3g around the particles; docs/MODEL.md section 14)\n",
                     look.summary.box_nu, look.summary.mean_nu);
      }
    }
  } else {
    throw InputError("sizes", "give --sizes s1,...,sL or --cells METHOD");
  }
  if (parse_cost(o.cost) == CostKind::time && o.cells.empty())
    throw InputError("cost", "'time' chooses sizes: give --cells optimal instead of --sizes");
  return g;
}

Packing read_grid_packing(const GridOptions& o) {
  Packing p = read_packing(o.file, Isolation::child_process, kIsolatedReadBaseSeconds, o.frame);
  check_file_dimension(p.d, o.d, o.file);
  return p;
}

}  // namespace hgrid::cli
