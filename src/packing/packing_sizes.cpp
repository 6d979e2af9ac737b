#include "hgridlab/packing/packing_sizes.hpp"

#include <algorithm>
#include <array>

#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/excluded.hpp"
#include "hgridlab/base/progress.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/grid/geometry.hpp"

namespace hgrid {

namespace {

/// The sizes the request asks for, for radii `dist` at `mp`, fitted to the
/// periodic box of `fit` (whose radii they are).
std::vector<double> requested_sizes(const Distribution& dist, const ModelParams& mp, const Packing& fit,
                                    const SizeRequest& r) {
  if (r.time_model) {
    if (r.method != CellMethod::optimal) throw InputError("cost", "'time' applies to --cells optimal only");
    if (r.excluded_model) throw InputError("cost", "'time' and --excluded-sizes do not combine");
    if (r.levels) throw InputError("cost", "'time' chooses the number of levels itself; drop --levels");
    return time_optimal_sizes(dist, mp, *r.time_model, static_cast<double>(fit.size())).sizes;
  }
  std::vector<double> sizes = choose_cell_sizes(dist, mp, r.method, r.levels, r.q).sizes;
  if (r.excluded_model) {
    if (r.method != CellMethod::optimal) throw InputError("excluded-sizes", "applies to --cells optimal only");
    sizes = refine_sizes_excluded_reported(dist, mp, sizes).sizes;
  }
  return merge_fitted_levels(sizes_for_grid(sizes, 2 * dist.r_max()), fit);
}

/// A tilted box's grid searches the mapped packing: radii and sizes c times
/// larger in a box of the same lengths (grid/tilted.hpp), random centres at
/// packing fraction c^d nu (above 1 for dense sheared packings). Its sizes
/// are the mapped packing's, over c.
std::vector<double> tilted_model_sizes(const Packing& p, const SizeRequest& r, Search search, double K) {
  if (r.excluded_model) throw InputError("excluded-sizes", "a tilted box's grid searches mapped ellipsoids, not hard spheres");
  const double c = p.d == 2 ? p.tilted_box<2>().inflation() : p.tilted_box<3>().inflation();
  Packing m = p;
  m.tilt = {};
  for (auto& v : m.radii) v *= c;
  ModelParams mp{p.d, m.packing_fraction(), K, search};
  mp.overfull = true;
  std::vector<double> sizes = requested_sizes(Empirical(m.radii), mp, m, r);
  for (auto& v : sizes) v /= c;
  return sizes;
}

}  // namespace

std::vector<double> model_sizes(const Packing& p, const SizeRequest& r, Search search, double K) {
  if (p.size() == 0) throw InputError("cells", "the packing has no particles to fit sizes to");
  if (p.tilted()) return tilted_model_sizes(p, r, search, K);
  return requested_sizes(Empirical(p.radii), ModelParams{p.d, p.packing_fraction(), K, search}, p, r);
}

std::vector<double> merge_fitted_levels(std::vector<double> sizes, const Packing& p) {
  if (p.boundary != Boundary::periodic) return sizes;
  const auto cells = [&](double s) {  // the grid's layout of a level
    std::array<double, 3> n{};
    for (std::size_t a = 0; a < static_cast<std::size_t>(p.d); ++a) n[a] = cells_per_axis(p.box[a], s, p.boundary);
    return n;
  };
  std::vector<double> out;
  for (const double s : sizes) {
    if (!out.empty() && cells(out.back()) == cells(s)) out.back() = s;  // the same cells: one level, the upper size
    else out.push_back(s);
  }
  return out;
}

ExcludedSizes refine_sizes_excluded_reported(const Distribution& dist, const ModelParams& p,
                                             const std::vector<double>& sizes) {
  Progress progress(true, "sizes under the excluded-volume model");
  return refine_sizes_excluded(dist, p, sizes, {}, [&](double f, int n, double T) {
    progress.update(f, std::to_string(n) + " evaluations, T/N " + format_number(T));
  });
}

}  // namespace hgrid
