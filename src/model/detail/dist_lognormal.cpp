// Truncated log-normal: moments as closed forms in the normal CDF.
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_sf_erf.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "hgridlab/model/distribution.hpp"
#include "hgridlab/base/error.hpp"

namespace hgrid {

namespace {
constexpr double kInvSqrt2 = 0.70710678118654752440;
double Phi(double z) { return 0.5 * std::erfc(-z * kInvSqrt2); }
double Q(double z) { return 0.5 * std::erfc(z * kInvSqrt2); }
/// ln Q(z), accurate far in the upper tail where Q(z) underflows.
double log_Q(double z) { return std::log(0.5) + gsl_sf_log_erfc(z * kInvSqrt2); }

/// ln of the normal mass on [za, zb], za < zb, without underflow in either
/// tail (the moments of a wide log-normal shift z by k sigma, far into a tail).
double log_mass(double za, double zb) {
  if (za >= 0.0) return log_Q(za) + std::log1p(-std::exp(log_Q(zb) - log_Q(za)));
  if (zb <= 0.0) return log_Q(-zb) + std::log1p(-std::exp(log_Q(-za) - log_Q(-zb)));
  return std::log(Phi(zb) - Phi(za));
}
}  // namespace

LogNormal::LogNormal(double mu, double sigma, double r_min, double r_max)
    : mu_(mu), sigma_(sigma), rmin_(r_min), rmax_(r_max) {
  if (!std::isfinite(mu)) throw InputError("mu", "must be finite");
  if (!std::isfinite(sigma) || !(sigma > 0.0))
    throw InputError("sigma", "must be > 0 (got " + std::to_string(sigma) + ")");
  if (!std::isfinite(r_min) || !(r_min > 0.0))
    throw InputError("r_min", "must be > 0 (got " + std::to_string(r_min) + ")");
  if (!std::isfinite(r_max) || !(r_max > r_min))
    throw InputError("omega", "must be > 1 for a log-normal (r_max > r_min)");
  zlo_ = (std::log(rmin_) - mu_) / sigma_;
  zhi_ = (std::log(rmax_) - mu_) / sigma_;
  norm_ = mass(zlo_, zhi_);
  if (!(norm_ > 0.0)) throw InputError("sigma", "the truncation window [r_min, r_max] holds no mass");
}

LogNormal LogNormal::centred(double sigma, double omega, double r_min) {
  if (!std::isfinite(omega) || !(omega > 1.0))
    throw InputError("omega", "must be > 1 for a log-normal (got " + std::to_string(omega) + ")");
  return LogNormal(std::log(r_min) + 0.5 * std::log(omega), sigma, r_min, omega * r_min);
}

double LogNormal::mass(double za, double zb) const {
  if (!(zb > za)) return 0.0;
  return za > 0.0 ? Q(za) - Q(zb) : Phi(zb) - Phi(za);  // subtract the small tails
}

double LogNormal::pdf(double r) const {
  if (r < rmin_ || r > rmax_) return 0.0;
  const double z = (std::log(r) - mu_) / sigma_;
  return std::exp(-0.5 * z * z) / (2.5066282746310002 * sigma_ * r * norm_);
}

double LogNormal::cdf(double r) const {
  if (r <= rmin_) return 0.0;
  if (r >= rmax_) return 1.0;
  return mass(zlo_, (std::log(r) - mu_) / sigma_) / norm_;
}

double LogNormal::quantile(double u) const {
  if (!(u >= 0.0 && u <= 1.0)) throw InputError("u", "must be in [0, 1] (got " + std::to_string(u) + ")");
  const double z = zlo_ > 0.0 ? gsl_cdf_ugaussian_Qinv(Q(zlo_) - u * norm_)
                              : gsl_cdf_ugaussian_Pinv(Phi(zlo_) + u * norm_);
  return std::clamp(std::exp(mu_ + sigma_ * z), rmin_, rmax_);
}

double LogNormal::moment(double k, double a, double b) const {
  a = std::max(a, rmin_);
  b = std::min(b, rmax_);
  if (!(b > a)) return 0.0;
  // r^k times the log-normal density is exp(k mu + k^2 sigma^2 / 2) times a
  // log-normal density with mean mu + k sigma^2.
  const double za = (std::log(a) - mu_) / sigma_ - k * sigma_;
  const double zb = (std::log(b) - mu_) / sigma_ - k * sigma_;
  // In logarithms: for a wide distribution the factor overflows while the
  // mass underflows, and their product is an ordinary number.
  return std::exp(k * mu_ + 0.5 * k * k * sigma_ * sigma_ + log_mass(za, zb) - log_mass(zlo_, zhi_));
}

}  // namespace hgrid
