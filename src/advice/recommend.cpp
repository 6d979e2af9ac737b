#include "hgridlab/advice/recommend.hpp"

#include <algorithm>
#include <cmath>

#include "hgridlab/calibration/calibration.hpp"
#include "hgridlab/advice/lammps_fit.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/model/distribution.hpp"

namespace hgrid {

Recommendation recommend_cell_sizes(const std::vector<double>& radii, const ModelParams& p,
                                    const std::optional<TimeModelUse>& time) {
  validate(p);
  if (radii.empty()) throw InputError("radii", "no particles to choose cell sizes for");
  for (double r : radii)
    if (!(std::isfinite(r) && r > 0)) throw InputError("radii", "every radius must be finite and > 0 (got " + format_number(r) + ")");
  Recommendation out;
  out.r_min = *std::min_element(radii.begin(), radii.end());
  out.r_max = *std::max_element(radii.begin(), radii.end());
  std::vector<double> scaled(radii);
  for (double& r : scaled) r /= out.r_min;
  const Empirical dist(std::move(scaled));
  const std::vector<double> unit_sizes =
      time ? time_optimal_sizes(dist, p, time->coef, time->n).sizes
           : sizes_for_grid(choose_cell_sizes(dist, p, CellMethod::optimal).sizes, 2 * dist.r_max());
  if (time) {
    out.seconds = predict_seconds(time->coef, expected_time_terms(dist, p, unit_sizes, time->n));
    out.linked_cell_seconds = predict_seconds(time->coef, expected_time_terms(dist, p, {2 * dist.r_max()}, time->n));
  }
  out.model = evaluate_model(dist, p, unit_sizes);
  out.linked_cell = evaluate_model(dist, p, {2 * dist.r_max()});
  for (double s : unit_sizes) out.sizes.push_back(s * out.r_min);
  out.sizes = sizes_for_grid(out.sizes, 2 * out.r_max);  // the top level holds the largest particle despite rounding
  out.model.sizes = out.sizes;
  out.linked_cell_size = 2 * out.r_max;
  out.linked_cell.sizes = {out.linked_cell_size};
  return out;
}

void add_lammps_collections(Recommendation& r, const std::vector<double>& radii, int d, double nu) {
  r.lammps_collections = lammps_collections_for(radii, d, nu, &r.lammps_model_source);
}

std::vector<double> lammps_collections_for(const std::vector<double>& radii, int d, double nu, std::string* source) {
  std::vector<double> diameters(radii.size());
  double volume = 0;
  for (std::size_t k = 0; k < radii.size(); ++k) {
    diameters[k] = 2 * radii[k];
    volume += ball_volume(d, radii[k]);
  }
  std::sort(diameters.begin(), diameters.end());
  const std::vector<double> box(static_cast<std::size_t>(d), std::pow(volume / nu, 1.0 / d));
  return lammps_collections(diameters, box, lammps_coefficients(source)).bounds;
}

std::optional<TimeModelUse> choose_time_model(const std::string& cost, const KChoice& k, int d, double n) {
  if (cost != "auto") parse_cost(cost);  // refuses anything but count and time
  const bool want = cost == "time" || (cost == "auto" && k.source == KSource::calibration);
  if (!want) return std::nullopt;
  const std::optional<Calibration> cal = stored_calibration();
  if (cal && cal->time_model(d)) return TimeModelUse{cal->time_model(d)->coef, n};
  if (cost == "time") return TimeModelUse{calibrated_time_model(d, "cost").coef, n};
  return std::nullopt;
}

}  // namespace hgrid
