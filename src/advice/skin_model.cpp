#include "hgridlab/advice/skin_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "hgridlab/base/error.hpp"

namespace hgrid {
namespace {

/// <(a + b + s)^d> for independent radii a, b with raw moments m[0..d].
double mean_power(const std::array<double, 4>& m, int d, double s) {
  // (a + b + s)^d = sum over p + q + t = d of d! / (p! q! t!) a^p b^q s^t
  static constexpr double kFact[4] = {1, 1, 2, 6};
  double out = 0;
  for (int p = 0; p <= d; ++p)
    for (int q = 0; p + q <= d; ++q) {
      const int t = d - p - q;
      out += kFact[d] / (kFact[p] * kFact[q] * kFact[t]) * m[p] * m[q] * std::pow(s, t);
    }
  return out;
}

}  // namespace

double contact_value(int d, double nu) {
  if (d != 2 && d != 3) throw InputError("d", "must be 2 or 3");
  if (!(nu >= 0 && nu < 1)) throw InputError("nu", "must be in [0, 1) (got " + format_number(nu) + ")");
  const double e = 1 - nu;
  return d == 3 ? (1 - nu / 2) / (e * e * e) : (1 - 7 * nu / 16) / (e * e);
}

double structure_at_zero(int d, double nu) {
  if (d != 2 && d != 3) throw InputError("d", "must be 2 or 3");
  if (!(nu >= 0 && nu < 1)) throw InputError("nu", "must be in [0, 1) (got " + format_number(nu) + ")");
  const double e = 1 - nu;
  if (d == 3) return e * e * e * e / (1 + 4 * nu + 4 * nu * nu - 4 * nu * nu * nu + nu * nu * nu * nu);
  return e * e * e / (1 + nu + 3 * nu * nu / 8 - nu * nu * nu / 8);
}

double shell_pairs_per_particle(const Distribution& radii, int d, double nu, double skin) {
  if (!(skin >= 0)) throw InputError("skin", "must be >= 0");
  std::array<double, 4> m{};
  // Moments over (0, r_max]: every radius (the intervals are open below).
  const double total = radii.moment(0, 0.0, radii.r_max());
  for (int k = 0; k <= d; ++k) m[k] = radii.moment(k, 0.0, radii.r_max()) / total;
  const double per = nu / (2 * m[d]);  // pairs per particle per unit of <(a + b + s)^d>
  // The ideal gas's shell (g = 1) and its growth at contact, d <(a + b)^(d-1)>.
  const double bulk = per * (mean_power(m, d, skin) - mean_power(m, d, 0.0));
  const double slope0 = per * d * mean_power(m, d - 1, 0.0);
  // The excess over it: the pairs beyond contact the compressibility sum
  // rule leaves, E = (S(0) - 1 + n V_excl) / 2 per particle, with the excluded
  // volume n V_excl = nu <(a + b)^d> / <r^d>.
  const double gc = contact_value(d, nu);
  const double excess = 0.5 * (structure_at_zero(d, nu) - 1 + 2 * per * mean_power(m, d, 0.0));
  if (!(gc > 1 && excess > 0 && slope0 > 0)) return gc * bulk;
  const double xi = excess / ((gc - 1) * slope0);  // the layer that holds it: the shell's slope at contact is g_c's
  return bulk + excess * -std::expm1(-skin / xi);
}

SkinPrediction predict_skin(const SkinMeasurement& a, const SkinMeasurement& b, const Distribution& radii, int d,
                            double nu, double skin) {
  if (!(a.skin > 0 && b.skin > 0 && a.skin != b.skin))
    throw InputError("skin", "the two measured skins must be > 0 and differ");
  if (!(skin > 0)) throw InputError("skin", "must be > 0");
  const SkinMeasurement& lo = a.skin < b.skin ? a : b;
  const SkinMeasurement& hi = a.skin < b.skin ? b : a;
  const double sh_lo = shell_pairs_per_particle(radii, d, nu, lo.skin);
  const double sh_hi = shell_pairs_per_particle(radii, d, nu, hi.skin);
  const double sh = shell_pairs_per_particle(radii, d, nu, skin);
  SkinPrediction p;
  p.skin = skin;
  // The two measurements (windows of a run, not one state) resolve how the
  // costs grow with the list only when their lists differ enough
  // (kResolvedLengths) and the slope comes out >= 0. Otherwise (lists of
  // nearly one length, as in a dense bed at small skins, where timing noise
  // would set the slope) each cost is proportional to the list's length,
  // from the larger skin's measurement: the steepest growth a non-negative
  // per-particle part allows, so that no skin looks free.
  const double l_lo = lo.candidates_per_n, l_hi = hi.candidates_per_n;
  const bool resolved = l_hi > kResolvedLengths * l_lo;
  // The list's length: the two measured, joined (and continued) by the
  // shell's shape; if the larger skin's list is not the longer (two windows
  // of a changing run), proportional to the shell from the larger skin's.
  // Never below the contacts: a list holds at least those (continued below
  // s0, the shell's steep rise near contact could take it there).
  if (l_hi > l_lo) p.candidates_per_n = l_lo + (sh - sh_lo) / (sh_hi - sh_lo) * (l_hi - l_lo);
  else p.candidates_per_n = sh_hi > 0 ? l_hi * sh / sh_hi : l_hi;
  p.candidates_per_n = std::max(p.candidates_per_n, std::min(lo.contacts_per_n, hi.contacts_per_n));
  // Affine in the list's length: the value at L from the two measured.
  const auto at = [&](double y_lo, double y_hi) {
    const double slope = (y_hi - y_lo) / (l_hi - l_lo);
    if (resolved && slope >= 0) return std::max(0.0, y_lo + slope * (p.candidates_per_n - l_lo));
    return l_hi > 0 ? y_hi * p.candidates_per_n / l_hi : y_hi;
  };
  // Steps per build: ballistic, from the measurement at the nearer skin
  // (from its travel per step and its growth where it rebuilt at nearly
  // every step).
  const SkinMeasurement& near = std::abs(std::log(skin / lo.skin)) < std::abs(std::log(skin / hi.skin)) ? lo : hi;
  if (near.steps_per_build < kCensoredSteps && near.travel_per_step > 0) {
    const double b = near.travel_growth > 0 ? std::clamp(std::log2(near.travel_growth), kRandomWalkExponent, 1.0) : 1.0;
    p.steps_per_build = std::max(1.0, std::pow(skin / near.travel_per_step, 1 / b));
  } else {
    p.steps_per_build = std::max(1.0, near.steps_per_build * skin / near.skin);
  }
  const double grid = 0.5 * (lo.seconds_grid + hi.seconds_grid), check = 0.5 * (lo.seconds_check + hi.seconds_check);
  p.seconds_per_step =
      (grid + at(lo.seconds_store, hi.seconds_store)) / p.steps_per_build + at(lo.seconds_test, hi.seconds_test) + check;
  return p;
}

SkinPrediction choose_skin(const SkinMeasurement& a, const SkinMeasurement& b, const Distribution& radii, int d,
                           double nu, double lo, double hi, int points) {
  if (!(lo > 0 && hi >= lo)) throw InputError("skin", "the range must have 0 < lo <= hi");
  points = std::max(points, 2);
  const auto cost = [&](double s) { return predict_skin(a, b, radii, d, nu, s); };
  SkinPrediction best = cost(lo);
  int at = 0;
  const double ratio = std::pow(hi / lo, 1.0 / (points - 1));
  for (int k = 1; k < points; ++k) {
    const SkinPrediction p = cost(lo * std::pow(ratio, k));
    if (p.seconds_per_step < best.seconds_per_step) best = p, at = k;
  }
  // Golden sections in log s between the scan's neighbours of its best.
  double x0 = std::log(lo * std::pow(ratio, std::max(0, at - 1)));
  double x1 = std::log(lo * std::pow(ratio, std::min(points - 1, at + 1)));
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int it = 0; it < 40; ++it) {
    const double u = x1 - g * (x1 - x0), v = x0 + g * (x1 - x0);
    const SkinPrediction pu = cost(std::exp(u)), pv = cost(std::exp(v));
    if (pu.seconds_per_step < pv.seconds_per_step) x1 = v;
    else x0 = u;
    if (pu.seconds_per_step < best.seconds_per_step) best = pu;
    if (pv.seconds_per_step < best.seconds_per_step) best = pv;
  }
  return best;
}

}  // namespace hgrid
