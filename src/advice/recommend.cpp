#include "hgridlab/advice/recommend.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "hgridlab/calibration/calibration.hpp"
#include "hgridlab/advice/lammps_fit.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/grid/tilted_box.hpp"
#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/time_model.hpp"

namespace hgrid {

namespace {

/// The radii in units of r_min (sorted once; recommend_in_units).
struct UnitRadii {
  double r_min = 0, r_max = 0;
  std::shared_ptr<const Empirical> dist;
};

UnitRadii unit_radii(const std::vector<double>& radii) {
  if (radii.empty()) throw InputError("radii", "no particles to choose cell sizes for");
  for (double r : radii)
    if (!(std::isfinite(r) && r > 0)) throw InputError("radii", "every radius must be finite and > 0 (got " + format_number(r) + ")");
  UnitRadii u;
  u.r_min = *std::min_element(radii.begin(), radii.end());
  u.r_max = *std::max_element(radii.begin(), radii.end());
  std::vector<double> scaled(radii);
  for (double& r : scaled) r /= u.r_min;
  u.dist = std::make_shared<const Empirical>(std::move(scaled));
  return u;
}

/// recommend_cell_sizes on radii already in units of r_min.
Recommendation recommend_in_units(const UnitRadii& u, const ModelParams& p, const std::optional<TimeModelUse>& time) {
  validate(p);
  Recommendation out;
  out.r_min = u.r_min;
  out.r_max = u.r_max;
  const Empirical& dist = *u.dist;
  const std::vector<double> unit_sizes =
      time ? time_optimal_sizes(dist, p, time->coef, time->n, time->box_volume / std::pow(out.r_min, p.d)).sizes
           : sizes_for_grid(choose_cell_sizes(dist, p, CellMethod::optimal).sizes, 2 * dist.r_max());
  if (time) {
    const double v = time->box_volume / std::pow(out.r_min, p.d);  // in units of r_min, as dist
    out.seconds = predict_seconds(time->coef, expected_time_terms(dist, p, unit_sizes, time->n, v));
    out.linked_cell_seconds = predict_seconds(time->coef, expected_time_terms(dist, p, {2 * dist.r_max()}, time->n, v));
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

}  // namespace

Recommendation recommend_cell_sizes(const std::vector<double>& radii, const ModelParams& p,
                                    const std::optional<TimeModelUse>& time) {
  validate(p);
  return recommend_in_units(unit_radii(radii), p, time);
}

Recommendation recommend_tilted(const std::vector<double>& radii, const ModelParams& p, double inflation,
                                const std::optional<TimeModelUse>& time) {
  if (!(std::isfinite(inflation) && inflation >= 1))
    throw InputError("tilt", "the box's inflation must be finite and >= 1 (got " + format_number(inflation) + ")");
  if (inflation == 1) return recommend_cell_sizes(radii, p, time);
  std::vector<double> mapped(radii);
  for (double& r : mapped) r *= inflation;
  ModelParams mp = p;
  mp.nu = p.nu * std::pow(inflation, p.d);
  mp.overfull = true;
  Recommendation out = recommend_cell_sizes(mapped, mp, time);
  for (double& s : out.sizes) s /= inflation;
  out.r_min /= inflation;
  out.r_max /= inflation;
  out.sizes = sizes_for_grid(out.sizes, 2 * out.r_max);  // the top level holds the largest particle despite rounding
  out.model.sizes = out.sizes;
  out.linked_cell_size = 2 * out.r_max;
  out.linked_cell.sizes = {out.linked_cell_size};
  out.tilt_inflation = inflation;
  return out;
}

double tilt_inflation(int d, std::span<const double> length, const std::array<double, 3>& tilt) {
  if (d != 2 && d != 3) throw InputError("d", "must be 2 or 3");
  if (length.size() < static_cast<std::size_t>(d)) throw InputError("box", "must hold d = " + std::to_string(d) + " side lengths");
  if (d == 2) return TiltedBox<2>{{length[0], length[1]}, {tilt[0], 0.0, 0.0}}.inflation();
  return TiltedBox<3>{{length[0], length[1], length[2]}, tilt}.inflation();
}

double tilt_inflation(const ParticleSet& s) {
  if (!s.tilted() || !s.box) return 1.0;
  return tilt_inflation(s.d, *s.box, s.tilt);
}

Recommendation recommend_for_field(const DensityField& field, const ModelParams& p,
                                   std::optional<TimeModelUse> time) {
  if (time) time->box_volume = field.volume();  // the grid lays out cells over the whole box
  const std::vector<double>& radii = field.radii();
  ModelParams q = p;
  q.d = field.d();
  q.nu = std::min(1.0, field.box_nu());
  validate(q);
  const UnitRadii unit = unit_radii(radii);
  const Empirical dist(radii);  // in the radii's unit (the field's and the time model's sizes)
  const Recommendation homogeneous = recommend_in_units(unit, q, time);
  const double window = 3 * 2 * homogeneous.r_max;
  FieldUse use;
  use.summary = field.summary(window);
  use.homogeneous_sizes = homogeneous.sizes;
  struct Best {
    double cost = INFINITY;
    Recommendation r;
    ModelResult model;
    double nu_eff = 0;
  } best;
  const auto consider = [&](Recommendation r) {
    FieldResult fr = field.evaluate(q, r.sizes);
    const double nu_eff = std::clamp(fr.effective_nu, 1e-6, 1.0);
    double cost = fr.model.T_over_N;
    if (time) {
      ModelParams at = q;
      at.nu = nu_eff;
      cost = predict_seconds(time->coef, expected_time_terms(dist, at, r.sizes, time->n, time->box_volume)).total();
    }
    if (cost < best.cost) best = Best{cost, std::move(r), std::move(fr.model), nu_eff};
  };
  if (!use.far_from_homogeneous()) {
    // Close to homogeneous: the paper's sizes at the box's nu (on the
    // figures' packings as good as the field's, or better by 1-2 % with
    // walls: docs/MODEL.md section 14), with the field's prediction.
    consider(homogeneous);
  } else {
    // Candidates: the homogeneous optima over a ladder of nu, and the fixed
    // point nu -> sizes -> the field's effective nu for them.
    std::vector<double> ladder;
    for (int k = 1; k <= 15; ++k) ladder.push_back(0.05 * k);
    double nu = std::clamp(use.summary.mean_nu, 0.01, 0.75);
    for (int it = 0; it < 4; ++it) {
      q.nu = nu;
      const double next =
          std::clamp(field.evaluate(q, recommend_in_units(unit, q, time).sizes).effective_nu, 0.01, 0.75);
      const bool settled = std::abs(next - nu) < 0.005;
      nu = next;
      if (settled) break;
    }
    ladder.push_back(nu);
    for (double x : ladder) {
      q.nu = x;
      consider(recommend_in_units(unit, q, time));
      if (time) consider(recommend_in_units(unit, q, std::nullopt));  // the count's optimum too: the time model judges
    }
    if (time) {  // and the linked cell
      Recommendation lc = homogeneous;
      lc.sizes = {homogeneous.linked_cell_size};
      consider(std::move(lc));
    }
  }
  Recommendation out = std::move(best.r);
  q.nu = best.nu_eff;
  out.model = best.model;
  out.model.sizes = out.sizes;
  const FieldResult lcf = field.evaluate(q, {out.linked_cell_size});
  out.linked_cell = lcf.model;
  out.linked_cell.sizes = {out.linked_cell_size};
  if (time) {
    out.seconds = predict_seconds(time->coef, expected_time_terms(dist, q, out.sizes, time->n, field.volume()));
    ModelParams lc = q;
    lc.nu = std::clamp(lcf.effective_nu, 1e-6, 1.0);
    out.linked_cell_seconds =
        predict_seconds(time->coef, expected_time_terms(dist, lc, {out.linked_cell_size}, time->n, field.volume()));
  }
  use.nu_effective = best.nu_eff;
  use.homogeneous_T_over_N = homogeneous.sizes == out.sizes
                                 ? homogeneous.model.T_over_N
                                 : evaluate_model(dist, ModelParams{field.d(), std::min(1.0, field.box_nu()), p.K, p.search}, out.sizes).T_over_N;
  use.homogeneous_sizes_T_over_N = field.evaluate(q, homogeneous.sizes).model.T_over_N;
  out.field = std::move(use);
  return out;
}

std::optional<DensityField> density_field_of(const Packing& p) {
  if (p.size() == 0 || p.tilted()) return std::nullopt;
  const bool per = p.boundary == Boundary::periodic;
  return DensityField(p.positions, p.radii, FieldBox{p.d, p.box, {per, per, per}});
}

std::optional<DensityField> density_field_of(const ParticleSet& s) {
  if (!s.has_positions() || !s.box || s.tilted() || (s.d != 2 && s.d != 3)) return std::nullopt;
  FieldBox box{s.d, *s.box, s.periodic_per_axis()};
  return DensityField(s.positions, s.radii, box);
}

Recommendation recommend_for_packing(const Packing& p, double K, Search search) {
  const ModelParams mp{p.d, std::min(1.0, p.packing_fraction()), K, search};
  const std::optional<DensityField> field = density_field_of(p);
  Recommendation r = field          ? recommend_for_field(*field, mp)
                     : p.tilted()     ? recommend_tilted(p.radii, mp, tilt_inflation(p.d, p.box, p.tilt))
                                      : recommend_cell_sizes(p.radii, mp);
  add_lammps_collections(r, p.radii, p.d, r.field ? r.field->nu_effective : mp.nu);
  return r;
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
