// Cell-size methods (docs/MODEL.md section 4) and the search for L*.
#include "hgridlab/model/cell_sizes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hgridlab/model/detail/model_sizes.hpp"
#include "hgridlab/base/error.hpp"

namespace hgrid {

namespace {
constexpr int kSearchCap = kMaxLevels;  // the L* scan stops here at the latest
constexpr int kConstantSearchCap = 256;  // ... and here for the constant method (shooting)
constexpr int kOptimalSearchCap = 256;   // ... and here for the optimal method
constexpr int kFlatPatience = 3;       // optimal: stop after this many L without gain
constexpr int kMinScan = 16;           // fixed methods: scan at least L = 1..16 ...
constexpr double kScanFactor = 2.0;    // ... and up to 2 L_best + kScanExtra
constexpr int kScanExtra = 10;
constexpr int kPlateauSkip = 2;        // optimal sweep: after this many L without gain ...
constexpr double kPlateauRelTol = 1e-12;  // ... (relative), add collapsed levels only
constexpr int kExtraStartsMaxL = 64;   // fixed-L optimum: also start from linear/constant

void check_q(double q) {
  if (!std::isfinite(q) || !(q > 0.0))
    throw InputError("q", "ratio of particles per cell must be finite and > 0 (got " + std::to_string(q) + ")");
}
void check_levels(int L) {
  if (L < 1 || L > kMaxLevels)
    throw InputError("levels", "must be in [1, " + std::to_string(kMaxLevels) + "] (got " + std::to_string(L) + ")");
}

// Eq. (34): s_h = 2 r_min (1 + h (omega - 1) / L).
std::vector<double> linear(const detail::CostModel& cm, int L) {
  std::vector<double> s(L);
  for (int h = 1; h <= L; ++h) s[h - 1] = cm.s0() + (cm.sL() - cm.s0()) * h / L;
  s[L - 1] = cm.sL();
  return s;
}
// Eq. (36): s_h = 2 r_min omega^(h/L).
std::vector<double> exponential(const detail::CostModel& cm, int L) {
  std::vector<double> s(L);
  const double lw = std::log(cm.sL() / cm.s0());
  for (int h = 1; h <= L; ++h) s[h - 1] = std::min(cm.sL(), cm.s0() * std::exp(lw * h / L));
  s[L - 1] = cm.sL();
  return s;
}
/// The L-1 optimum with its widest log-gap split in two: a warm start for L.
std::vector<double> split_widest(const detail::CostModel& cm, const std::vector<double>& prev) {
  std::size_t at = 0;
  double widest = -1.0, lo = cm.s0();
  for (std::size_t i = 0; i < prev.size(); ++i) {
    const double gap = std::log(prev[i] / lo);
    if (gap > widest) widest = gap, at = i;
    lo = prev[i];
  }
  std::vector<double> s = prev;
  const double below = at == 0 ? cm.s0() : prev[at - 1];
  s.insert(s.begin() + static_cast<long>(at), std::sqrt(below * prev[at]));
  return s;
}
/// The L-1 sizes plus an empty level: the top one doubled (Top-Down never
/// scans above a particle) or s_0 prepended (Bottom-Up never scans below).
std::vector<double> collapsed(const detail::CostModel& cm, const std::vector<double>& prev) {
  std::vector<double> s = prev;
  if (cm.params().search == Search::top_down) s.push_back(cm.sL());
  else s.insert(s.begin(), cm.s0());
  return s;
}

/// Optimal sizes for L = 1, 2, ... with warm starts; T is non-increasing in L.
/// Calls visit(L, sizes, T) for each L; stops when visit returns false.
template <class Visit>
void optimal_sweep(const detail::CostModel& cm, int max_levels, Visit&& visit) {
  std::vector<double> prev{cm.sL()};
  double T_prev = cm.total(prev);
  if (!visit(1, prev, T_prev)) return;
  int plateau = 0;  // consecutive L that gained nothing: extra levels collapse
  for (int L = 2; L <= max_levels; ++L) {
    std::vector<double> c = collapsed(cm, prev);
    const double Tc = cm.total(c);
    std::vector<double> s;
    double T = Tc;
    if (plateau < kPlateauSkip) {
      s = detail::optimise_sizes(cm, L, {split_widest(cm, prev), exponential(cm, L)});
      T = cm.total(s);
    }
    if (!(T < Tc)) s = std::move(c), T = Tc;
    plateau = T < T_prev * (1.0 - kPlateauRelTol) ? 0 : plateau + 1;
    if (!visit(L, s, T)) return;
    prev = std::move(s);
    T_prev = T;
  }
}
/// Optimal sizes for one L: the warm-started sweep up to L (so the result is
/// never worse than any smaller L) and Newton from the other methods' sizes.
std::vector<double> optimal_fixed(const detail::CostModel& cm, int L) {
  std::vector<double> best;
  double T_best = 0.0;
  optimal_sweep(cm, L, [&](int l, const std::vector<double>& s, double T) {
    if (l == L) best = s, T_best = T;
    return true;
  });
  if (L > 1 && L <= kExtraStartsMaxL) {
    auto s = detail::optimise_sizes(cm, L, {linear(cm, L), detail::constant_ratio_sizes(cm, L, 1.0)});
    if (cm.total(s) < T_best) best = std::move(s);
  }
  return best;
}

std::vector<double> sizes_by(const detail::CostModel& cm, CellMethod method, int L, double q) {
  switch (method) {
    case CellMethod::linear: return linear(cm, L);
    case CellMethod::exponential: return exponential(cm, L);
    case CellMethod::constant: return detail::constant_ratio_sizes(cm, L, q);
    case CellMethod::optimal: return optimal_fixed(cm, L);
  }
  return {};
}

SizeChoice make_choice(const detail::CostModel& cm, std::vector<double> s) {
  SizeChoice c;
  c.levels = static_cast<int>(s.size());
  c.model = cm.detailed(s);
  c.sizes = std::move(s);
  return c;
}

}  // namespace

CellMethod parse_cell_method(const std::string& name, const std::string& field) {
  if (name == "linear") return CellMethod::linear;
  if (name == "exponential") return CellMethod::exponential;
  if (name == "constant") return CellMethod::constant;
  if (name == "optimal") return CellMethod::optimal;
  throw InputError(field, "must be one of linear, exponential, constant, optimal (got '" + name + "')");
}

const char* to_string(CellMethod m) {
  switch (m) {
    case CellMethod::linear: return "linear";
    case CellMethod::exponential: return "exponential";
    case CellMethod::constant: return "constant";
    case CellMethod::optimal: return "optimal";
  }
  return "?";
}

std::vector<double> cell_sizes(const Distribution& dist, const ModelParams& p, CellMethod method,
                               int levels, double q) {
  check_levels(levels);
  check_q(q);
  const detail::CostModel cm(dist, p);
  return sizes_by(cm, method, levels, q);
}

SizeChoice choose_cell_sizes(const Distribution& dist, const ModelParams& p, CellMethod method,
                             std::optional<int> levels, double q) {
  check_q(q);
  if (levels) check_levels(*levels);
  const detail::CostModel cm(dist, p);
  if (levels) return make_choice(cm, sizes_by(cm, method, *levels, q));
  if (!(p.K >= kMinSearchK))
    throw InputError("K", "the best number of levels is searched only for K >= " + format_number(kMinSearchK) + " (got " +
                              format_number(p.K) + "): with cheaper cell accesses more levels keep paying; give a fixed number of levels");
  const auto at_cap = [&](int cap) {
    return InputError("K", "no best number of levels up to " + std::to_string(cap) + " (K = " + format_number(p.K) +
                               "): more levels keep paying; give a fixed number of levels or a larger K");
  };

  if (method == CellMethod::optimal) {
    std::vector<std::pair<std::vector<double>, double>> runs;
    double T_min = std::numeric_limits<double>::infinity();
    int since_gain = 0;
    int L_reached = 0;
    optimal_sweep(cm, kOptimalSearchCap, [&](int L, const std::vector<double>& s, double T) {
      L_reached = L;
      since_gain = (T < T_min * (1.0 - kLevelsFlatRelTol)) ? 0 : since_gain + 1;
      T_min = std::min(T_min, T);
      runs.emplace_back(s, T);
      return since_gain < kFlatPatience;
    });
    if (since_gain < kFlatPatience && L_reached >= kOptimalSearchCap) throw at_cap(kOptimalSearchCap);
    for (auto& [s, T] : runs)
      if (T <= T_min * (1.0 + kLevelsFlatRelTol)) return make_choice(cm, s);
  }
  int L_best = 1;
  double T_best = std::numeric_limits<double>::infinity();
  const int cap = method == CellMethod::constant ? kConstantSearchCap : kSearchCap;
  for (int L = 1; L <= cap; ++L) {
    if (L > kMinScan && L > kScanFactor * L_best + kScanExtra) break;
    const double T = cm.total(sizes_by(cm, method, L, q));
    if (T < T_best) T_best = T, L_best = L;
  }
  if (L_best == cap) throw at_cap(cap);
  return make_choice(cm, sizes_by(cm, method, L_best, q));
}

std::vector<double> cost_versus_levels(const Distribution& dist, const ModelParams& p,
                                       CellMethod method, int max_levels, double q) {
  check_levels(max_levels);
  check_q(q);
  const detail::CostModel cm(dist, p);
  std::vector<double> T;
  if (method == CellMethod::optimal) {
    optimal_sweep(cm, max_levels, [&](int, const std::vector<double>&, double t) {
      T.push_back(t);
      return true;
    });
  } else {
    for (int L = 1; L <= max_levels; ++L) T.push_back(cm.total(sizes_by(cm, method, L, q)));
  }
  return T;
}

std::vector<double> sizes_for_grid(std::vector<double> s, double largest_diameter) {
  if (s.empty()) throw InputError("sizes", "no cell sizes");
  s.erase(std::unique(s.begin(), s.end(), [](double a, double b) { return !(b > a); }), s.end());
  s.back() = std::max(s.back(), largest_diameter);
  return s;
}

}  // namespace hgrid
