#include "hgridlab/packing/rcp.hpp"

#include <algorithm>
#include <cmath>

#include "hgridlab/base/error.hpp"

namespace hgrid {

double virtual_packing_density(std::vector<SizeClass> classes, double beta) {
  if (!(beta > 0 && beta < 1)) throw InputError("beta", "must be in (0, 1)");
  std::erase_if(classes, [](const SizeClass& c) { return !(c.volume_share > 0); });
  if (classes.empty()) throw InputError("classes", "need at least one size class with a positive volume share");
  double total = 0;
  for (const auto& c : classes) {
    if (!(c.diameter > 0) || !std::isfinite(c.diameter)) throw InputError("diameter", "must be positive and finite");
    total += c.volume_share;
  }
  const std::size_t n = classes.size();
  double best = 1;
  for (std::size_t i = 0; i < n; ++i) {
    const double di = classes[i].diameter;
    double s = 0;
    for (std::size_t j = 0; j < n; ++j) {
      const double y = classes[j].volume_share / total, dj = classes[j].diameter;
      if (dj > di) {  // coarser: wall effect
        const double b = 1 - std::pow(1 - di / dj, kWallExponent);
        s += (1 - beta + b * beta * (1 - 1 / beta)) * y;
      } else if (dj < di) {  // finer: loosening effect
        const double a = std::sqrt(1 - std::pow(1 - dj / di, kLooseningExponent));
        s += (1 - a) * y;
      }
    }
    best = std::min(best, beta / (1 - s));
  }
  return best;
}

double estimate_rcp(int d, const Distribution& dist) {
  if (d != 2 && d != 3) throw InputError("d", "must be 2 or 3");
  const double beta = d == 2 ? kMonoRcp2 : kMonoRcp3;
  const double lo = dist.r_min(), hi = dist.r_max();
  if (!(hi > lo * (1 + 1e-9))) return beta;
  std::vector<SizeClass> classes;
  classes.reserve(kRcpClasses);
  for (int i = 0; i < kRcpClasses; ++i) {
    const double a = lo * std::pow(hi / lo, static_cast<double>(i) / kRcpClasses);
    const double b = lo * std::pow(hi / lo, static_cast<double>(i + 1) / kRcpClasses);
    const double m = dist.moment(d, i == 0 ? 0 : a, b);  // volume of the class (up to a constant)
    if (!(m > 0)) continue;
    const double r = dist.moment(d + 1, i == 0 ? 0 : a, b) / m;  // volume-weighted mean radius
    classes.push_back({2 * r, m});
  }
  return virtual_packing_density(std::move(classes), beta);
}

}  // namespace hgrid
