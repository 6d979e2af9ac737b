// Numerically stable pieces of the power-law closed forms (docs/MODEL.md section 5).
#pragma once
#include <cmath>
#include <limits>

namespace hgrid::detail {

/// log of g(x) = expm1(x) / x (g(0) = 1); g > 0 for every real x.
inline double log_expm1_over_x(double x) {
  if (x == 0.0) return 0.0;
  if (x > 50.0) return x + std::log1p(-std::exp(-x)) - std::log(x);
  return std::log(std::expm1(x) / x);
}

/// log of integral_a^b x^(e-1) dx = (b^e - a^e) / e for 0 < a < b, written as
/// a^e ln(b/a) g(e ln(b/a)) so that e -> 0 (where it becomes ln(b/a)), b/a -> 1
/// and b/a up to 1e6 and beyond stay accurate. -inf for b <= a.
inline double log_power_integral(double e, double a, double b) {
  if (!(b > a)) return -std::numeric_limits<double>::infinity();
  const double lr = std::log1p((b - a) / a);  // accurate for b close to a
  return e * std::log(a) + std::log(lr) + log_expm1_over_x(e * lr);
}

}  // namespace hgrid::detail
