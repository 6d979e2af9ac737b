#include "model/detail/walls.hpp"

#include <algorithm>
#include <cmath>

namespace hgrid::detail {

namespace {
constexpr int kSamplesPerCell = 64;  // midpoint rule in x; the integrand is piecewise linear
constexpr int kMinSamples = 4096;
}  // namespace

AxisScan scan_axis(double A, double a, double s, bool own, double beta, const std::vector<double>& b) {
  AxisScan out;
  out.fraction.assign(b.size(), 0.0);
  const long n = std::max(1L, static_cast<long>(std::ceil(A / s)));
  const double lo = std::min(a, 0.5 * A), hi = std::max(A - a, 0.5 * A);
  const long M = std::max<long>(kMinSamples, kSamplesPerCell * n);
  const auto cell = [&](double x) { return std::clamp(static_cast<long>(std::floor(x / s)), 0L, n - 1); };
  for (long m = 0; m < M; ++m) {
    const double x = lo + (hi - lo) * (m + 0.5) / M;
    long c0, c1;
    if (own) {
      const long i = cell(x);
      c0 = std::max(0L, i - 1), c1 = std::min(n - 1, i + 1);
      out.p_below += i >= 1 ? 1.0 : 0.0;
      out.p_above += i <= n - 2 ? 1.0 : 0.0;
    } else {
      c0 = cell(x - beta), c1 = cell(x + beta);
    }
    out.cells += static_cast<double>(c1 - c0 + 1);
    const double y0 = c0 * s, y1 = (c1 + 1) * s;
    for (std::size_t q = 0; q < b.size(); ++q) {
      const double blo = std::min(b[q], 0.5 * A), bhi = std::max(A - b[q], 0.5 * A);
      const double len = bhi - blo;
      const double cover = std::max(0.0, std::min(y1, bhi) - std::max(y0, blo));
      out.fraction[q] += len > 0 ? cover / len : 1.0;
    }
  }
  out.cells /= M;
  out.p_below /= M;
  out.p_above /= M;
  for (double& f : out.fraction) f /= M;
  return out;
}

}  // namespace hgrid::detail
