// Particle-radius distributions behind one interface (docs/MODEL.md section 2).
// Every integral the cost model needs is a partial moment
//   moment(k, a, b) = integral_a^b r^k f(r) dr,
// so a distribution only has to supply those (closed form where possible,
// GSL quadrature of pdf() otherwise).
#pragma once
#include <cstddef>
#include <utility>
#include <vector>

namespace hgrid {

class Distribution {
 public:
  virtual ~Distribution() = default;

  virtual double r_min() const = 0;
  virtual double r_max() const = 0;
  double omega() const { return r_max() / r_min(); }

  /// Probability density on [r_min, r_max] (0 outside). For Empirical it is a
  /// histogram estimate, used for plots and as a smooth guide only.
  virtual double pdf(double r) const = 0;
  /// P(R <= r).
  virtual double cdf(double r) const = 0;
  /// Inverse CDF: the smallest r with cdf(r) >= u, u in [0, 1]. The default
  /// inverts cdf() numerically; subclasses override with closed forms.
  virtual double quantile(double u) const;

  /// integral of r^k f(r) dr over the radii in the half-open interval (a, b]
  /// (the radii a level of cell size s owns are (s_prev/2, s/2]); the cost
  /// model passes a = 0 for the lowest level. Returns 0 for b <= a.
  /// The default integrates pdf() with GSL's adaptive quadrature (QAGS).
  virtual double moment(double k, double a, double b) const;

  /// out[k] = moment(k, a, b) for k = 0..kmax, the same values; Empirical
  /// finds the interval's radii once for all k (the cost model's inner loop).
  virtual void moments(int kmax, double a, double b, double* out) const {
    for (int k = 0; k <= kmax; ++k) out[k] = moment(k, a, b);
  }

  /// Quadrature of r^k pdf(r) over [a, b] regardless of any closed form;
  /// for tests and for subclasses without one.
  double moment_by_quadrature(double k, double a, double b) const;

  /// True when cdf() is continuous and pdf() is its exact derivative, so
  /// gradient-based optimisers may use it.
  virtual bool smooth() const { return true; }

  /// Draw n radii by inverse-CDF sampling, reproducible from `seed`.
  std::vector<double> sample(std::size_t n, unsigned long long seed) const;
};

/// Truncated power law f(r) = C r^alpha on [r_min, omega r_min] (Eq. 29-30).
/// Closed-form moments, stable at exponents where a moment is a logarithm
/// (alpha + k + 1 = 0), for omega from 1 (a delta at r_min) to 1e6 and beyond.
class PowerLaw : public Distribution {
 public:
  PowerLaw(double alpha, double omega, double r_min = 1.0);
  double alpha() const { return alpha_; }
  double r_min() const override { return rmin_; }
  double r_max() const override { return rmax_; }
  double pdf(double r) const override;
  double cdf(double r) const override;
  double quantile(double u) const override;
  double moment(double k, double a, double b) const override;
  bool smooth() const override { return rmax_ > rmin_; }

 private:
  double alpha_, omega_, rmin_, rmax_;
  double log_norm_;  // log of integral_1^omega x^alpha dx (r_min units)
};

/// Log-normal truncated to [r_min, r_max]: ln R ~ Normal(mu, sigma^2)
/// conditioned on r_min <= R <= r_max. `centred` puts the median of the
/// untruncated law at the geometric mean sqrt(r_min r_max), mu = ln r_min +
/// ln(omega)/2, which is what `hgrid model --dist lognormal --sigma S` uses.
/// Moments are closed forms in the normal CDF (no quadrature).
class LogNormal : public Distribution {
 public:
  LogNormal(double mu, double sigma, double r_min, double r_max);
  static LogNormal centred(double sigma, double omega, double r_min = 1.0);
  double mu() const { return mu_; }
  double sigma() const { return sigma_; }
  double r_min() const override { return rmin_; }
  double r_max() const override { return rmax_; }
  double pdf(double r) const override;
  double cdf(double r) const override;
  double quantile(double u) const override;
  double moment(double k, double a, double b) const override;
  bool smooth() const override { return rmax_ > rmin_; }

 private:
  double mass(double za, double zb) const;  // Phi(zb) - Phi(za), tail-accurate
  double mu_, sigma_, rmin_, rmax_;
  double zlo_, zhi_, norm_;                   // standardised bounds, their mass
};

/// The empirical distribution of a list of radii (any positive values, in the
/// user's length unit). Sorted once with prefix sums of r^0..r^4, so cdf and
/// integer moments cost one binary search each (fine for 1e6 radii).
class Empirical : public Distribution {
 public:
  explicit Empirical(std::vector<double> radii);
  std::size_t size() const { return r_.size(); }
  const std::vector<double>& sorted_radii() const { return r_; }
  double r_min() const override { return r_.front(); }
  double r_max() const override { return r_.back(); }
  double pdf(double r) const override;
  double cdf(double r) const override;
  double quantile(double u) const override;
  double moment(double k, double a, double b) const override;
  void moments(int kmax, double a, double b, double* out) const override;
  bool smooth() const override { return false; }

 private:
  /// Indices [lo, hi) of the sorted radii in (a, b].
  std::pair<std::size_t, std::size_t> interval(double a, double b) const;
  /// integral of r^k f over radii lo..hi-1 from the prefix sums (k <= kMaxPrefix).
  double prefix_moment(int k, std::size_t lo, std::size_t hi) const;

  static constexpr int kMaxPrefix = 4;
  std::vector<double> r_;
  std::vector<long double> prefix_[kMaxPrefix + 1];  // prefix_[k][i] = sum_{<i} r^k
  std::vector<double> hist_;                         // pdf histogram on [r_min, r_max]
};

}  // namespace hgrid
