// Constant ratio of particles per cell, m_{h+1} = q m_h (Eqs. 37-39).
#include <algorithm>
#include <cmath>
#include <limits>

#include "hgridlab/model/detail/model_sizes.hpp"

namespace hgrid::detail {

namespace {
constexpr double kLogSizeTol = 1e-13;  // bracket width in ln s at convergence
constexpr int kMaxRootSteps = 300;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// Smallest x in [lo, hi] with f(x) >= 0 for a non-decreasing f with
/// f(lo) < 0 <= f(hi); f may jump (step CDFs) or be +inf (overshoot).
/// Illinois false position, falling back to bisection when it stalls.
template <class F>
double solve_increasing(F&& f, double lo, double hi, double flo, double fhi) {
  int side = 0;
  double width_before = hi - lo;  // bracket width three steps ago
  for (int it = 0; it < kMaxRootSteps && hi - lo > kLogSizeTol; ++it) {
    const double width = hi - lo;
    const bool stalled = it % 3 == 2 && width > 0.5 * width_before;
    if (it % 3 == 2) width_before = width;
    double x = 0.5 * (lo + hi);
    if (std::isfinite(fhi) && !stalled) {
      x = lo - flo * width / (fhi - flo);
      const double guard = 1e-3 * kLogSizeTol;
      if (!(x > lo + guard && x < hi - guard)) x = 0.5 * (lo + hi);
    }
    const double fx = f(x);
    if (fx == 0.0) return x;
    if (fx < 0) {
      lo = x, flo = fx;
      if (side == -1) fhi *= 0.5;
      side = -1;
    } else {
      hi = x, fhi = fx;
      if (side == 1) flo *= 0.5;
      side = 1;
    }
  }
  return hi;
}
}  // namespace

std::vector<double> constant_ratio_sizes(const CostModel& cm, int L, double q) {
  const double s0 = cm.s0(), sL = cm.sL();
  std::vector<double> s(L, sL);
  if (L == 1 || !(sL > s0)) return s;
  const Distribution& dist = cm.dist();
  const int d = cm.params().d;
  const double c = cm.params().nu / cm.mean_volume(), rmax = dist.r_max();
  // m of a level spanning sizes (a, b]: nu b^d P / V_p (Eq. 1).
  auto m_of = [&](double a, double b) { return c * std::pow(b, d) * dist.moment(0, 0.5 * a, 0.5 * b); };
  const double x0 = std::log(s0), xL = std::log(sL);
  // Smooth CDFs: solve ln m(a, e^y) = ln target by Newton in y, kept inside
  // the bracket [ln a, ln s_L]; ln m is nearly linear in y. Level h starts
  // from its solution in the previous shot (the shots converge onto each
  // other), else from ln s_L.
  std::vector<double> warm(L, kInf);
  auto newton_log = [&](int h, double a, double target) {
    double lo = std::log(a), hi = xL, y = warm[h] > lo && warm[h] < hi ? warm[h] : hi;
    const auto done = [&](double v) { return warm[h] = v; };
    const double lt = std::log(target);
    for (int it = 0; it < kMaxRootSteps && hi - lo > kLogSizeTol; ++it) {
      const double b = std::exp(y), P = dist.moment(0, 0.5 * a, 0.5 * b);
      const double g = std::log(c * std::pow(b, d) * P) - lt;
      if (g == 0.0) return done(y);
      (g < 0.0 || !(P > 0.0) ? lo : hi) = y;
      const double dg = d + 0.5 * b * dist.pdf(0.5 * b) / P;
      double yn = y - g / dg;
      // Converged: checked before the bracket test, since y has just become
      // one of the bracket's ends and a tiny step would fall onto it.
      if (std::isfinite(g) && std::fabs(yn - y) < kLogSizeTol) return done(std::clamp(yn, lo, hi));
      if (!(yn > lo && yn < hi) || !std::isfinite(g)) yn = 0.5 * (lo + hi);
      y = yn;
    }
    return done(hi);
  };

  // Shoot from s_1 = e^x1 through m_{h+1} = q m_h, letting sizes run past
  // s_L; returns ln(s_L(x1) / s_L), non-decreasing in x1 (+inf when no
  // particle is left for a level).
  auto shoot = [&](double x1, bool keep) -> double {
    double prev = std::exp(x1), mprev = m_of(0.0, prev);
    if (keep) s[0] = std::min(prev, sL);
    for (int h = 1; h < L; ++h) {
      const double target = q * mprev, a = prev;
      if (a >= sL) return kInf;
      double next;
      if (!(target > 0.0)) {
        next = a;
      } else if (m_of(a, sL) >= target) {
        next = std::exp(dist.smooth() ? newton_log(h, a, target)
                                      : solve_increasing([&](double y) { return m_of(a, std::exp(y)) - target; },
                                                         std::log(a), xL, -target, m_of(a, sL) - target));
      } else {  // beyond s_L the level holds every radius above a/2: closed form
        next = std::pow(target / (c * dist.moment(0, 0.5 * a, rmax)), 1.0 / d);
      }
      mprev = next > sL ? target : m_of(a, next);
      prev = next;
      if (keep && h < L - 1) s[h] = std::min(prev, sL);
    }
    return std::log(prev) - xL;
  };
  const double flo = shoot(x0, false);
  double x1 = x0;
  if (flo < 0) x1 = solve_increasing([&](double x) { return shoot(x, false); }, x0, xL, flo, shoot(xL, false));
  shoot(x1, true);
  s[L - 1] = sL;
  for (int h = 1; h < L; ++h) s[h] = std::max(s[h], s[h - 1]);
  return s;
}

}  // namespace hgrid::detail
