// Haff's law for a freely cooling granular gas (P. K. Haff, J. Fluid Mech.
// 134 (1983) 401): E(t) = E0 / (1 + t/t0)^2 while the gas stays homogeneous,
// so E^(-1/2) grows linearly in t. The fit is a least-squares line of
// E^(-1/2) against t; r2 measures how straight it is.
#pragma once
#include <cmath>
#include <vector>

namespace hgrid::dpm {

struct HaffFit {
  double t0 = 0;  // Haff time (E0 from the intercept)
  double E0 = 0;
  double r2 = 0;
};

inline HaffFit fit_haff(const std::vector<double>& t, const std::vector<double>& E) {
  const std::size_t n = t.size();
  double st = 0, sy = 0, stt = 0, sty = 0, syy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double y = 1.0 / std::sqrt(E[i]);
    st += t[i], sy += y, stt += t[i] * t[i], sty += t[i] * y, syy += y * y;
  }
  const double vt = stt - st * st / n, vy = syy - sy * sy / n, c = sty - st * sy / n;
  const double slope = c / vt, icpt = (sy - slope * st) / n;
  HaffFit f;
  f.E0 = 1.0 / (icpt * icpt);
  f.t0 = icpt / slope;
  f.r2 = vy > 0 ? c * c / (vt * vy) : 1.0;
  return f;
}

}  // namespace hgrid::dpm
