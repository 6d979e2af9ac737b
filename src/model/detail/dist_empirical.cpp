// Empirical distribution of a list of radii: sorted once, prefix sums of r^k.
#include <algorithm>
#include <cmath>
#include <string>

#include "hgridlab/model/distribution.hpp"
#include "hgridlab/base/error.hpp"

namespace hgrid {

namespace {
constexpr std::size_t kMaxHistBins = 200;
}

Empirical::Empirical(std::vector<double> radii) : r_(std::move(radii)) {
  if (r_.empty()) throw InputError("radii", "need at least one radius");
  for (double r : r_)
    if (!std::isfinite(r) || !(r > 0.0))
      throw InputError("radii", "every radius must be finite and > 0 (got " + std::to_string(r) + ")");
  std::sort(r_.begin(), r_.end());
  const std::size_t n = r_.size();
  for (int k = 0; k <= kMaxPrefix; ++k) {
    auto& p = prefix_[k];
    p.assign(n + 1, 0.0L);
    for (std::size_t i = 0; i < n; ++i) {
      long double v = 1.0L;
      for (int j = 0; j < k; ++j) v *= r_[i];
      p[i + 1] = p[i] + v;
    }
  }
  if (r_.back() > r_.front()) {
    const std::size_t nb = std::clamp<std::size_t>(
        static_cast<std::size_t>(std::sqrt(static_cast<double>(n))), 1, kMaxHistBins);
    hist_.assign(nb, 0.0);
    const double w = (r_.back() - r_.front()) / static_cast<double>(nb);
    for (double r : r_)
      hist_[std::min(nb - 1, static_cast<std::size_t>((r - r_.front()) / w))] += 1.0;
    for (auto& h : hist_) h /= static_cast<double>(n) * w;
  }
}

double Empirical::pdf(double r) const {
  if (hist_.empty() || r < r_min() || r > r_max()) return 0.0;
  const double w = (r_max() - r_min()) / static_cast<double>(hist_.size());
  return hist_[std::min(hist_.size() - 1, static_cast<std::size_t>((r - r_min()) / w))];
}

double Empirical::cdf(double r) const {
  const auto it = std::upper_bound(r_.begin(), r_.end(), r);
  return static_cast<double>(it - r_.begin()) / static_cast<double>(r_.size());
}

double Empirical::quantile(double u) const {
  if (!(u >= 0.0 && u <= 1.0)) throw InputError("u", "must be in [0, 1] (got " + std::to_string(u) + ")");
  const double n = static_cast<double>(r_.size());
  const auto idx = static_cast<std::size_t>(std::max(0.0, std::ceil(u * n) - 1.0));
  return r_[std::min(idx, r_.size() - 1)];
}

std::pair<std::size_t, std::size_t> Empirical::interval(double a, double b) const {
  // Radii in (a, b]: indices [lo, hi) of the sorted radii.
  const auto lo = static_cast<std::size_t>(std::upper_bound(r_.begin(), r_.end(), a) - r_.begin());
  const auto hi = static_cast<std::size_t>(std::upper_bound(r_.begin(), r_.end(), b) - r_.begin());
  return {lo, hi};
}

double Empirical::prefix_moment(int k, std::size_t lo, std::size_t hi) const {
  if (hi <= lo) return 0.0;
  return static_cast<double>((prefix_[k][hi] - prefix_[k][lo]) / static_cast<long double>(r_.size()));
}

double Empirical::moment(double k, double a, double b) const {
  const auto [lo, hi] = interval(a, b);
  if (hi <= lo) return 0.0;
  const double kr = std::round(k);
  if (kr == k && kr >= 0.0 && kr <= kMaxPrefix) return prefix_moment(static_cast<int>(kr), lo, hi);
  long double s = 0.0L;
  for (std::size_t i = lo; i < hi; ++i) s += std::pow(r_[i], k);
  return static_cast<double>(s / static_cast<long double>(r_.size()));
}

void Empirical::moments(int kmax, double a, double b, double* out) const {
  if (kmax > kMaxPrefix) {
    Distribution::moments(kmax, a, b, out);
    return;
  }
  const auto [lo, hi] = interval(a, b);  // once for every k
  for (int k = 0; k <= kmax; ++k) out[k] = prefix_moment(k, lo, hi);
}

}  // namespace hgrid
