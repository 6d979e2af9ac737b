#include "hgrid/rcp.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "hgrid/error.hpp"

namespace hgrid {
namespace {

struct RodClass {
  double length;  // rod length (diameter), in units where the line is 1
  double share;   // share of the particle volume
};

/// Gap lengths are merged into log bins of this relative width to bound the work.
constexpr double kGapBin = 1e-3;

/// Can the rods fill a total length phi of the unit line?
bool feasible(const std::vector<RodClass>& classes, double phi, double phi_c) {
  std::map<long, std::pair<double, double>, std::greater<>> gaps;  // bin -> (count, length sum)
  auto add_gap = [&gaps](double g, double count) {
    if (count <= 0 || g <= 0) return;
    const long bin = std::lround(std::log(g) / kGapBin);
    auto& e = gaps[bin];
    e.first += count;
    e.second += count * g;
  };
  add_gap(1.0, 1.0);
  for (const auto& c : classes) {
    double need = phi * c.share;  // length to place
    std::vector<std::pair<double, double>> produced;  // (sub-gap, count)
    for (auto it = gaps.begin(); it != gaps.end() && need > 0;) {
      auto& [count, sum] = it->second;
      const double g = sum / count;
            const double n = std::floor(phi_c * g / c.length);
      if (n < 1) break;  // this gap and every shorter one is too small
      const double cap = count * n * c.length;
      const double used = need >= cap ? count : count * need / cap;
      need -= used * n * c.length;
      produced.emplace_back((g - n * c.length) / (n + 1), used * (n + 1));
      count -= used;
      sum = count * g;
      if (count <= 1e-300) it = gaps.erase(it);
      else ++it;
    }
    if (need > 1e-12 * phi) return false;
    for (const auto& [g, k] : produced) add_gap(g, k);
    // Gaps shorter than the smallest rod can never be used again.
    const double smallest = classes.back().length;
    while (!gaps.empty() && gaps.rbegin()->second.second / gaps.rbegin()->second.first < smallest)
      gaps.erase(std::prev(gaps.end()));
  }
  return true;
}

}  // namespace

double estimate_rcp(int d, const Distribution& dist) {
  if (d != 2 && d != 3) throw InputError("d", "must be 2 or 3");
  const double phi_c = d == 2 ? kMonoRcp2 : kMonoRcp3;
  const double lo = dist.r_min(), hi = dist.r_max();
  if (!(hi > lo * (1 + 1e-9))) return phi_c;
  // Rod lengths: the line is 1e6 largest diameters long ("infinite").
  const double unit = 1e-6 / (2 * hi);
  const double total = dist.moment(d, 0, hi);
  std::vector<RodClass> classes;
  for (int i = kRcpClasses - 1; i >= 0; --i) {
    const double a = lo * std::pow(hi / lo, static_cast<double>(i) / kRcpClasses);
    const double b = lo * std::pow(hi / lo, static_cast<double>(i + 1) / kRcpClasses);
    const double m = dist.moment(d, i == 0 ? 0 : a, b);
    if (m <= 0) continue;
    const double r = dist.moment(d + 1, i == 0 ? 0 : a, b) / m;  // volume-weighted mean radius
    classes.push_back({2 * r * unit, m / total});
  }
  double ok = phi_c * 0.9, bad = 1.0;
  while (bad - ok > kRcpTol) {
    const double mid = 0.5 * (ok + bad);
    (feasible(classes, mid, phi_c) ? ok : bad) = mid;
  }
  return ok;
}

}  // namespace hgrid
