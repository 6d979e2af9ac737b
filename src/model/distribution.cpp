// Distribution base class (quadrature, inverse-CDF sampling) and PowerLaw.
#include "hgridlab/model/distribution.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "hgridlab/model/detail/dist_math.hpp"
#include "hgridlab/base/error.hpp"

namespace hgrid {

namespace {
constexpr double kQuadRelTol = 1e-12;   // QAGS relative tolerance
constexpr std::size_t kQuadLimit = 2000;  // QAGS subintervals
constexpr int kBisectSteps = 200;         // generic quantile bisection

struct QuadData {
  const Distribution* dist;
  double k;
};
// Integrand in u = ln r: r^(k+1) f(r), which keeps wide ranges well resolved.
double log_integrand(double u, void* p) {
  const auto* q = static_cast<const QuadData*>(p);
  const double r = std::exp(u);
  return std::exp((q->k + 1.0) * u) * q->dist->pdf(r);
}
}  // namespace

double Distribution::quantile(double u) const {
  if (!(u >= 0.0 && u <= 1.0)) throw InputError("u", "must be in [0, 1] (got " + std::to_string(u) + ")");
  double lo = r_min(), hi = r_max();
  if (cdf(lo) >= u) return lo;
  for (int i = 0; i < kBisectSteps && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (cdf(mid) >= u ? hi : lo) = mid;
  }
  return hi;
}

double Distribution::moment(double k, double a, double b) const {
  return moment_by_quadrature(k, a, b);
}

double Distribution::moment_by_quadrature(double k, double a, double b) const {
  a = std::max(a, r_min());
  b = std::min(b, r_max());
  if (!(b > a)) return 0.0;
  gsl_set_error_handler_off();
  std::unique_ptr<gsl_integration_workspace, decltype(&gsl_integration_workspace_free)> ws(
      gsl_integration_workspace_alloc(kQuadLimit), &gsl_integration_workspace_free);
  QuadData data{this, k};
  gsl_function fn{&log_integrand, &data};
  double result = 0.0, err = 0.0;
  gsl_integration_qags(&fn, std::log(a), std::log(b), 0.0, kQuadRelTol, kQuadLimit, ws.get(),
                       &result, &err);  // roundoff warnings keep the best estimate
  return result;
}

std::vector<double> Distribution::sample(std::size_t n, unsigned long long seed) const {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<double> out(n);
  for (auto& r : out) r = quantile(uni(rng));
  return out;
}

// ---------------------------------------------------------------- PowerLaw
PowerLaw::PowerLaw(double alpha, double omega, double r_min)
    : alpha_(alpha), omega_(omega), rmin_(r_min), rmax_(omega * r_min), log_norm_(0.0) {
  if (!std::isfinite(alpha) || std::fabs(alpha) > 100.0)
    throw InputError("alpha", "must be a finite number in [-100, 100] (got " + std::to_string(alpha) + ")");
  if (!std::isfinite(omega) || !(omega >= 1.0) || omega > 1e12)
    throw InputError("omega", "must be >= 1 and <= 1e12 (got " + std::to_string(omega) + ")");
  if (!std::isfinite(r_min) || !(r_min > 0.0))
    throw InputError("r_min", "must be > 0 (got " + std::to_string(r_min) + ")");
  // Eq. (30): C = 1 / integral_1^omega x^alpha dx (in units of r_min).
  if (omega > 1.0) log_norm_ = detail::log_power_integral(alpha + 1.0, 1.0, omega);
}

double PowerLaw::pdf(double r) const {
  if (r < rmin_ || r > rmax_ || rmax_ == rmin_) return 0.0;
  return std::exp(alpha_ * std::log(r / rmin_) - log_norm_) / rmin_;  // Eq. (29)
}

double PowerLaw::cdf(double r) const {
  if (r < rmin_) return 0.0;
  if (r >= rmax_) return 1.0;
  return std::exp(detail::log_power_integral(alpha_ + 1.0, 1.0, r / rmin_) - log_norm_);
}

double PowerLaw::quantile(double u) const {
  if (!(u >= 0.0 && u <= 1.0)) throw InputError("u", "must be in [0, 1] (got " + std::to_string(u) + ")");
  if (rmax_ == rmin_) return rmin_;
  // Invert x^e = 1 + u (omega^e - 1), e = alpha + 1, without overflow.
  const double e = alpha_ + 1.0, lw = std::log(omega_);
  double lx;
  if (e == 0.0) lx = u * lw;
  else if (e * lw > 1.0) lx = lw + std::log(u + (1.0 - u) * std::exp(-e * lw)) / e;
  else lx = std::log1p(u * std::expm1(e * lw)) / e;
  return std::clamp(rmin_ * std::exp(lx), rmin_, rmax_);
}

double PowerLaw::moment(double k, double a, double b) const {
  if (rmax_ == rmin_)  // delta at r_min, owned by the interval (a, b] containing it
    return (a < rmin_ && b >= rmin_) ? std::pow(rmin_, k) : 0.0;
  const double xa = std::max(a, rmin_) / rmin_, xb = std::min(b, rmax_) / rmin_;
  if (!(xb > xa)) return 0.0;
  // integral_xa^xb x^(alpha+k) dx / integral_1^omega x^alpha dx, scaled by r_min^k.
  return std::pow(rmin_, k) *
         std::exp(detail::log_power_integral(alpha_ + k + 1.0, xa, xb) - log_norm_);
}

}  // namespace hgrid
