#include "hgridlab/packing/detail/gen_stationary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hgrid::detail {

Stationarity test_stationary(std::span<const double> series, double rel_tol, std::size_t min_samples) {
  Stationarity t;
  const std::size_t n = series.size();
  if (n < std::max<std::size_t>(min_samples, 4)) return t;
  const std::size_t first = n / 2, m = n - first;
  // Least squares y = a + b x, x = ln(sweeps).
  double xm = 0, ym = 0;
  for (std::size_t k = first; k < n; ++k) {
    xm += std::log(static_cast<double>((k + 1) * kStationarySampleSweeps));
    ym += series[k];
  }
  xm /= static_cast<double>(m);
  ym /= static_cast<double>(m);
  double sxx = 0, sxy = 0;
  for (std::size_t k = first; k < n; ++k) {
    const double dx = std::log(static_cast<double>((k + 1) * kStationarySampleSweeps)) - xm;
    sxx += dx * dx;
    sxy += dx * (series[k] - ym);
  }
  const double b = sxy / sxx;
  // Residuals; successive samples are correlated (a few sweeps apart), so
  // the standard error is widened by the lag-1 autocorrelation rho of the
  // residuals as for an AR(1) series, sqrt((1 + rho) / (1 - rho)).
  double rss = 0, lag = 0, prev = 0;
  for (std::size_t k = first; k < n; ++k) {
    const double r = series[k] - ym - b * (std::log(static_cast<double>((k + 1) * kStationarySampleSweeps)) - xm);
    rss += r * r;
    if (k > first) lag += r * prev;
    prev = r;
  }
  const double rho = rss > 0 ? std::clamp(lag / rss, 0.0, kStationaryMaxRho) : 0.0;
  const double se_b = std::sqrt(rss / static_cast<double>(m - 2) / sxx * (1 + rho) / (1 - rho));
  t.samples = m;
  t.mean = ym;
  t.drift = b * std::log(2.0);
  t.se = se_b * std::log(2.0);
  t.stationary = std::abs(t.drift) + 2 * t.se <= rel_tol * std::abs(ym);
  return t;
}

std::string stationarity_rule(double rel_tol, std::size_t min_samples) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "stationary(drift/doubling+2se<=%.17g,every=%d,min=%zu)", rel_tol,
                kStationarySampleSweeps, min_samples);
  return buf;
}

}  // namespace hgrid::detail
