// Public entry points of the cost model: validation and evaluation.
#include "hgridlab/model/model.hpp"

#include <cmath>
#include <string>

#include "hgridlab/model/detail/model_cost.hpp"
#include "hgridlab/base/error.hpp"

namespace hgrid {

namespace {
constexpr double kTopSizeRelTol = 1e-12;  // s_L may undershoot 2 r_max by rounding

void validate_sizes(const Distribution& dist, const std::vector<double>& s) {
  if (s.empty()) throw InputError("levels", "need at least one level (L >= 1)");
  for (std::size_t h = 0; h < s.size(); ++h) {
    if (!std::isfinite(s[h]) || !(s[h] > 0.0))
      throw InputError("sizes", "every cell size must be finite and > 0 (s_" + std::to_string(h + 1) +
                                    " = " + format_number(s[h]) + ")");
    if (h > 0 && s[h] < s[h - 1])
      throw InputError("sizes", "cell sizes must be non-decreasing (s_" + std::to_string(h + 1) +
                                    " < s_" + std::to_string(h) + ")");
  }
  if (s.back() < 2.0 * dist.r_max() * (1.0 - kTopSizeRelTol))
    throw InputError("sizes", "the largest cell size must be >= 2 r_max = " + format_number(2.0 * dist.r_max()) +
                                  " (got " + format_number(s.back()) + ")");
}
}  // namespace

void validate(const ModelParams& p) {
  if (p.d != 2 && p.d != 3) throw InputError("d", "must be 2 or 3 (got " + std::to_string(p.d) + ")");
  if (!(p.nu > 0.0 && (p.nu <= 1.0 || (p.overfull && std::isfinite(p.nu)))))
    throw InputError("nu", "packing fraction must be in (0, 1] (got " + format_number(p.nu) + ")");
  if (!std::isfinite(p.K) || !(p.K >= 0.0))
    throw InputError("K", "must be finite and >= 0 (got " + format_number(p.K) + ")");
}

ModelResult evaluate_model(const Distribution& dist, const ModelParams& p,
                           const std::vector<double>& sizes) {
  validate_sizes(dist, sizes);
  return detail::CostModel(dist, p).detailed(sizes);
}

double cross_level_cells(const Distribution& dist, int d, const std::vector<double>& s, int j, int h) {
  const int L = static_cast<int>(s.size());
  if (j < 1 || j > L || h < 1 || h > L)
    throw InputError("level", "j and h must be in [1, L] (got j = " + std::to_string(j) +
                                  ", h = " + std::to_string(h) + ")");
  if (d != 2 && d != 3) throw InputError("d", "must be 2 or 3 (got " + std::to_string(d) + ")");
  const double lo = h == 1 ? 0.0 : 0.5 * s[h - 2], hi = 0.5 * s[h - 1];
  const double P = dist.moment(0, lo, hi);
  if (!(P > 0.0)) return 0.0;
  // Eq. (16): b(j,h) = (1/P_h) int (2 + 2r/s_j)^d f(r) dr, expanded in moments.
  double b = 0.0, binom = 1.0;
  for (int i = 0; i <= d; ++i) {
    b += std::pow(2.0, d) * binom * std::pow(s[j - 1], -i) * dist.moment(i, lo, hi);
    binom = binom * (d - i) / (i + 1);
  }
  return b / P;
}

}  // namespace hgrid
