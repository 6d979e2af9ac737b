#include "hgridlab/model/detail/walls.hpp"

#include <algorithm>
#include <cmath>

namespace hgrid::detail {

namespace {
constexpr int kSamplesPerCell = 256;  // midpoint rule in x (the densities jump at contact: ~1e-4 of T/N)
constexpr int kMinSamples = 16384;

double wall_h(const WallProfile& p, double z) {
  if (z < p.radius) return -1.0;
  if (p.h.empty()) return 0.0;
  if (z < p.contact) return -1.0;
  const double t = z / p.dz;
  auto i = static_cast<std::size_t>(t);
  if (static_cast<double>(i) * p.dz < p.contact) ++i;  // the node below is inside contact: extrapolate from above
  if (i + 1 >= p.h.size()) return 0.0;
  return p.h[i] + (t - static_cast<double>(i)) * (p.h[i + 1] - p.h[i]);
}

// Density at x, 0 outside the class's accessible region [r, A - r].
double density(const WallProfile& p, double A, double x) {
  if (x < p.radius || x > A - p.radius) return 0.0;
  return std::max(0.0, 1.0 + wall_h(p, x) + wall_h(p, A - x));
}
}  // namespace

AxisScan scan_axis(double A, const WallProfile& a, double s, bool own, double beta, const std::vector<WallProfile>& b,
                   double layer) {
  AxisScan out;
  out.fraction.assign(b.size(), 0.0);
  out.fraction_interior.assign(b.size(), 0.0);
  const long n = std::max(1L, static_cast<long>(std::ceil(A / s)));
  const long M = std::max<long>(kMinSamples, kSamplesPerCell * n);
  const double dx = A / M;
  // Cumulative distributions of the searched classes on the sample grid.
  std::vector<std::vector<double>> cum(b.size(), std::vector<double>(M + 1, 0.0));
  for (std::size_t q = 0; q < b.size(); ++q) {
    for (long m = 0; m < M; ++m) cum[q][m + 1] = cum[q][m] + density(b[q], A, (m + 0.5) * dx);
    const double total = cum[q][M];
    for (double& c : cum[q]) c = total > 0 ? c / total : 0.0;
  }
  const auto cdf = [&](std::size_t q, double y) {
    const double t = std::clamp(y / dx, 0.0, double(M));
    const auto i = std::min<long>(static_cast<long>(t), M - 1);
    return cum[q][i] + (t - i) * (cum[q][i + 1] - cum[q][i]);
  };
  const auto cell = [&](double x) { return std::clamp(static_cast<long>(std::floor(x / s)), 0L, n - 1); };
  double wsum = 0.0;
  for (long m = 0; m < M; ++m) {
    const double x = (m + 0.5) * dx, w = density(a, A, x);
    if (w <= 0) continue;
    wsum += w;
    long c0, c1;
    if (own) {
      const long i = cell(x);
      c0 = std::max(0L, i - 1), c1 = std::min(n - 1, i + 1);
      out.p_below += i >= 1 ? w : 0.0;
      out.p_above += i <= n - 2 ? w : 0.0;
    } else {
      c0 = cell(x - beta), c1 = cell(x + beta);
    }
    out.cells += w * static_cast<double>(c1 - c0 + 1);
    const bool interior = x >= layer && x <= A - layer;
    for (std::size_t q = 0; q < b.size(); ++q) {
      const double f = w * (cdf(q, (c1 + 1) * s) - cdf(q, c0 * s));
      out.fraction[q] += f;
      if (interior) out.fraction_interior[q] += f;
    }
  }
  if (wsum > 0) {
    out.cells /= wsum;
    out.p_below /= wsum;
    out.p_above /= wsum;
    for (double& f : out.fraction) f /= wsum;
    for (double& f : out.fraction_interior) f /= wsum;
  }
  return out;
}

}  // namespace hgrid::detail
