// Optimal cell sizes for a given L (paper Sect. 5.2.4): minimise Eq. (27)
// over s_1..s_{L-1} subject to s_0 <= s_1 <= ... <= s_L.
//
// Damped Newton on t_k = ln s_k with the analytic gradient and a Hessian from
// forward differences of it; steps keep every gap t_k - t_{k-1} positive
// (fraction to the boundary), so a level may approach collapse but the order
// constraint never breaks. The cost is very flat in the sizes of the top levels
// (few particles live there), which defeats first-order and quasi-Newton
// methods; Newton converges in a few tens of steps.
#include <algorithm>
#include <cmath>
#include <limits>

#include "hgridlab/model/detail/model_sizes.hpp"

namespace hgrid::detail {

namespace {
constexpr int kMaxNewton = 200;
constexpr double kDecrementRelTol = 1e-14;  // stop when the Newton decrement is below this * T
constexpr double kArmijo = 1e-4;
constexpr double kUndamped = 1e-6;          // damping below which a step counts as Newton's
constexpr double kToBoundary = 0.9;         // a step may close at most 90 % of a gap
constexpr double kFdRel = 1e-4;             // Hessian difference step, relative to the gaps
constexpr double kMinGapRel = 1e-13;        // starts: gaps at least this * ln(omega)
constexpr double kCollapseRel = 1e-9;       // a gap this small (* ln omega) closes: the two
                                            // sides then move together until released
constexpr int kPolishGrid = 24;             // grid points per coordinate in the polish
constexpr int kPolishSweeps = 30;
constexpr double kPolishRelTol = 1e-12;

struct Newton {
  const CostModel& cm;
  int L;
  double t0, tL;
  std::vector<double> s, gs;

  double eval(const std::vector<double>& t) {
    to_sizes(t);
    return cm.total(s);
  }
  double grad(const std::vector<double>& t, std::vector<double>& g) {
    to_sizes(t);
    const double T = cm.total_and_gradient(s, gs);
    g.resize(L - 1);
    for (int k = 0; k < L - 1; ++k) g[k] = s[k] * gs[k];
    return T;
  }
  void to_sizes(const std::vector<double>& t) {
    s.resize(L);
    for (int k = 0; k < L - 1; ++k) s[k] = std::exp(t[k]);
    s[L - 1] = cm.sL();
    for (int k = L - 2; k >= 0; --k) s[k] = std::min(s[k], s[k + 1]);
    s[0] = std::max(s[0], cm.s0());
    for (int k = 1; k < L - 1; ++k) s[k] = std::max(s[k], s[k - 1]);
  }
  double gap(const std::vector<double>& t, int k) const {  // t_k - t_{k-1}, k = 0..L-1
    return (k < L - 1 ? t[k] : tL) - (k > 0 ? t[k - 1] : t0);
  }
};

/// In-place Cholesky solve of A x = b (A n x n, row-major); false if not PD.
bool cholesky_solve(std::vector<double> A, std::vector<double>& b, int n) {
  for (int j = 0; j < n; ++j) {
    double d = A[j * n + j];
    for (int k = 0; k < j; ++k) d -= A[j * n + k] * A[j * n + k];
    if (!(d > 0.0)) return false;
    d = std::sqrt(d);
    A[j * n + j] = d;
    for (int i = j + 1; i < n; ++i) {
      double v = A[i * n + j];
      for (int k = 0; k < j; ++k) v -= A[i * n + k] * A[j * n + k];
      A[i * n + j] = v / d;
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < i; ++k) b[i] -= A[i * n + k] * b[k];
    b[i] /= A[i * n + i];
  }
  for (int i = n - 1; i >= 0; --i) {
    for (int k = i + 1; k < n; ++k) b[i] -= A[k * n + i] * b[k];
    b[i] /= A[i * n + i];
  }
  return true;
}

/// Groups of variables moved together: a closed gap ties its two sides (a
/// level collapsed onto its neighbour); groups tied to t_0 or t_L are fixed.
struct Ties {
  std::vector<char> closed;  // gap k (between t_{k-1} and t_k), k = 0..n
  std::vector<int> group;    // variable -> free group index, or -1 (fixed)
  int groups = 0;
  void rebuild(int n) {
    group.assign(n, -1);
    groups = 0;
    int k = 0;
    while (k < n) {
      int e = k;
      while (e + 1 < n && closed[e + 1]) ++e;  // variables k..e are tied together
      const bool fixed = (k == 0 && closed[0]) || (e == n - 1 && closed[n]);
      for (int i = k; i <= e; ++i) group[i] = fixed ? -1 : groups;
      if (!fixed) ++groups;
      k = e + 1;
    }
  }
};

/// Damped Newton from `start` (length L) with an active set of collapsed
/// levels; returns the sizes reached.
std::vector<double> newton(const CostModel& cm, int L, const std::vector<double>& start) {
  Newton nw{cm, L, std::log(cm.s0()), std::log(cm.sL()), {}, {}};
  const int n = L - 1;
  const double span = nw.tL - nw.t0, min_gap = kMinGapRel * span;
  std::vector<double> t(n);
  for (int k = 0; k < n; ++k) {
    const double lo = (k == 0 ? nw.t0 : t[k - 1]) + min_gap;
    const double hi = nw.tL - (n - k) * min_gap;
    t[k] = std::clamp(std::log(std::max(start[k], cm.s0())), lo, hi);
  }
  Ties ties{std::vector<char>(n + 1, 0), {}, 0};
  ties.rebuild(n);
  std::vector<double> g, g2, H, p, tn(n), tp(n), gr, dir(n);
  double T = nw.grad(t, g);
  double lambda = 0.0;
  for (int it = 0; it < kMaxNewton; ++it) {
    // Release the closed gap whose opening lowers T fastest (KKT sign test).
    int release = -1, release_sign = 0;  // +1: block above moves up; -1: block below down
    double best_rate = kDecrementRelTol * T;
    for (int k = 0; k <= n; ++k) {
      if (!ties.closed[k]) continue;
      double up = 0.0, down = 0.0;  // -dT for moving the block above k up / below k down
      for (int i = k; i < n && (i == k || ties.closed[i]); ++i) up -= g[i];
      for (int i = k - 1; i >= 0 && (i == k - 1 || ties.closed[i + 1]); --i) down += g[i];
      if (k < n && up > best_rate) best_rate = up, release = k, release_sign = 1;
      if (k > 0 && down > best_rate) best_rate = down, release = k, release_sign = -1;
    }
    if (release >= 0) {
      ties.closed[release] = 0;
      ties.rebuild(n);
    }
    const int m = ties.groups;
    if (m == 0) break;
    // Reduced gradient and forward-difference Hessian over the free groups.
    gr.assign(m, 0.0);
    for (int i = 0; i < n; ++i)
      if (ties.group[i] >= 0) gr[ties.group[i]] += g[i];
    H.assign(m * m, 0.0);
    for (int j = 0; j < m; ++j) {
      // Step into the wider of the group's two outer gaps, a small part of it.
      int first = -1, last = -1;
      for (int i = 0; i < n; ++i)
        if (ties.group[i] == j) last = i, first = first < 0 ? i : first;
      const double below = nw.gap(t, first), above = nw.gap(t, last + 1);
      double h = kFdRel * std::max(below, above);
      if (above < below) h = -h;
      if (h == 0.0) h = kFdRel * span;
      tp = t;
      for (int i = 0; i < n; ++i)
        if (ties.group[i] == j) tp[i] += h;
      nw.grad(tp, g2);
      for (int i = 0; i < n; ++i)
        if (ties.group[i] >= 0) H[ties.group[i] * m + j] += (g2[i] - g[i]) / h;
    }
    double hmax = 0.0;
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < i; ++j) H[i * m + j] = H[j * m + i] = 0.5 * (H[i * m + j] + H[j * m + i]);
    for (int i = 0; i < m; ++i) hmax = std::max(hmax, std::fabs(H[i * m + i]));
    bool accepted = false, converged = false;
    for (int tries = 0; tries < 40 && !accepted; ++tries) {
      std::vector<double> A = H;
      // Levenberg-Marquardt damping scaled per coordinate: the curvature of
      // the bottom levels exceeds that of the top ones by many decades.
      for (int i = 0; i < m; ++i) A[i * m + i] += lambda * (std::fabs(H[i * m + i]) + 1e-12 * hmax) + 1e-300;
      p = gr;
      for (auto& v : p) v = -v;
      if (!cholesky_solve(A, p, m)) {
        lambda = std::max(1e-12, 10.0 * lambda);
        continue;
      }
      double slope = 0.0;
      for (int i = 0; i < m; ++i) slope += gr[i] * p[i];
      if (-slope < kDecrementRelTol * T) {
        if (lambda <= kUndamped) {
          converged = true;
          break;
        }
        lambda = 0.0;  // a tiny damped step says nothing: retry undamped
        continue;
      }
      for (int i = 0; i < n; ++i) dir[i] = ties.group[i] >= 0 ? p[ties.group[i]] : 0.0;
      auto max_step = [&] {
        double tau = 1.0;
        for (int k = 0; k <= n; ++k) {  // keep every open gap open
          if (ties.closed[k]) continue;
          const double dg = (k < n ? dir[k] : 0.0) - (k > 0 ? dir[k - 1] : 0.0);
          if (dg < 0.0) tau = std::min(tau, -kToBoundary * nw.gap(t, k) / dg);
        }
        return tau;
      };
      double tau = max_step();
      // The block that opens the released gap; -1 if it is tied to an end
      // point (s_0 or s_L), which cannot move.
      const int release_grp = release < 0 ? -1 : ties.group[release_sign > 0 ? release : release - 1];
      if (tau <= 0.0 && release_grp >= 0) {
        // Newton would shut the gap just released: move only the block that
        // opens it, as the sign test said, and let the line search scale it.
        const int grp = release_grp;
        const double curv = std::max(std::fabs(H[grp * m + grp]), 1e-300);
        for (int i = 0; i < n; ++i)
          dir[i] = ties.group[i] == grp ? release_sign * std::min(0.1 * span, best_rate / curv) : 0.0;
        slope = 0.0;
        for (int i = 0; i < n; ++i) slope += g[i] * dir[i];
        tau = max_step();
      }
      for (int ls = 0; ls < 30; ++ls, tau *= 0.5) {
        for (int i = 0; i < n; ++i) tn[i] = t[i] + tau * dir[i];
        if (nw.eval(tn) <= T + kArmijo * tau * slope) {
          t = tn;
          accepted = true;
          break;
        }
      }
      if (accepted) lambda *= 0.1;
      else lambda = std::max(1e-12, 10.0 * lambda);
    }
    if (converged && release < 0) break;
    if (!accepted && !converged) break;
    // Close (tie) the gaps that have all but vanished.
    bool changed = false;
    for (int k = 0; k <= n; ++k)
      if (!ties.closed[k] && nw.gap(t, k) < kCollapseRel * span) ties.closed[k] = 1, changed = true;
    if (changed) {
      ties.rebuild(n);
      for (int k = 0; k < n; ++k) {  // snap tied variables onto their anchor
        if (ties.closed[k]) t[k] = k == 0 ? nw.t0 : t[k - 1];
      }
      for (int k = n - 1; k >= 0; --k)
        if (ties.closed[k + 1]) t[k] = k == n - 1 ? nw.tL : t[k + 1];
    }
    T = nw.grad(t, g);
  }
  nw.to_sizes(t);
  return nw.s;
}

/// Derivative-free coordinate descent: each interior s_k over [s_{k-1}, s_{k+1}]
/// on a log grid, then golden-section refinement around the best grid point.
/// Handles the jumps of an empirical (step) CDF.
double polish(const CostModel& cm, std::vector<double>& s) {
  const int L = static_cast<int>(s.size());
  double T = cm.total(s);
  for (int sweep = 0; sweep < kPolishSweeps; ++sweep) {
    const double T_start = T;
    for (int k = 0; k + 1 < L; ++k) {
      const double lo = std::log(k == 0 ? cm.s0() : s[k - 1]), hi = std::log(s[k + 1]);
      if (!(hi > lo)) continue;
      auto eval = [&](double x) {
        const double keep = s[k];
        s[k] = std::clamp(std::exp(x), std::exp(lo), s[k + 1]);
        const double v = cm.total(s);
        s[k] = keep;
        return v;
      };
      double best_x = std::log(s[k]), best = T;
      const double step = (hi - lo) / kPolishGrid;
      for (int i = 0; i <= kPolishGrid; ++i) {
        const double x = lo + i * step, v = eval(x);
        if (v < best) best = v, best_x = x;
      }
      double a = std::max(lo, best_x - step), b = std::min(hi, best_x + step);
      const double gr = 0.5 * (std::sqrt(5.0) - 1.0);
      double x1 = b - gr * (b - a), x2 = a + gr * (b - a), f1 = eval(x1), f2 = eval(x2);
      for (int it = 0; it < 60 && b - a > 1e-12; ++it) {
        if (f1 < f2) b = x2, x2 = x1, f2 = f1, x1 = b - gr * (b - a), f1 = eval(x1);
        else a = x1, x1 = x2, f1 = f2, x2 = a + gr * (b - a), f2 = eval(x2);
      }
      if (std::min(f1, f2) < best) best = std::min(f1, f2), best_x = f1 < f2 ? x1 : x2;
      if (best < T) {
        s[k] = std::clamp(std::exp(best_x), std::exp(lo), s[k + 1]);
        T = cm.total(s);
      }
    }
    if (T >= T_start * (1.0 - kPolishRelTol)) break;
  }
  return T;
}
}  // namespace

std::vector<double> optimise_sizes(const CostModel& cm, int L,
                                   const std::vector<std::vector<double>>& starts) {
  std::vector<double> best(L, cm.sL());
  if (L == 1 || !(cm.sL() > cm.s0())) return best;
  double T_best = std::numeric_limits<double>::infinity();
  for (const auto& st : starts) {
    std::vector<double> s = newton(cm, L, st);
    double T = cm.total(s);
    // A start may already beat what Newton reached (a damped step can stop early).
    const double T_st = cm.total(st);
    if (T_st < T) s = st, T = T_st;
    if (!cm.dist().smooth()) T = polish(cm, s);
    if (T < T_best) T_best = T, best = s;
  }
  return best;
}

}  // namespace hgrid::detail
