// Growth + FIRE. Energy E = 1/2 sum_pairs (delta_ij / sigma_ij)^2 with delta
// the overlap and sigma = r_i + r_j: the relative overlaps, which is also the
// convergence criterion. Unit masses; a pair's stiffness 1/sigma^2 makes a big
// sphere with many small neighbours no stiffer than a small one, so one time
// step suits all. Contacts come from a Verlet list (skin kSkin r_i) built with
// the HGrid and rebuilt only when a sphere has moved or grown through its skin;
// its partner lists are sorted, so the packing does not depend on the grid.
//
// Threads: the spheres (in spatial order) are cut into one range per thread,
// balanced by list pairs. A sphere's force is the sum, in canonical order, of
// its pairs (i, p) in increasing i, then its pairs (p, j) in increasing j,
// then the walls. A range's thread first adds, for its spheres, the pairs
// reaching in from earlier ranges (computed again there: a few per cent near
// the range's edge), then runs its rows as one thread does, adding to a
// partner's force only if the partner is in the range. Every sphere sees the
// same additions in the same order, so the packing does not depend on the
// number of threads. The FIRE sums (power, norms) stay one ordered loop.
#include "hgridlab/packing/detail/gen_relax.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "hgridlab/packing/detail/gen_pairs.hpp"

namespace hgrid::detail {
namespace {

// FIRE parameters (Bitzek et al. 2006, their recommended values).
constexpr int kFireNmin = 5;
constexpr double kFireFinc = 1.1, kFireFdec = 0.5, kFireAlpha0 = 0.1, kFireFalpha = 0.99;

template <int D, Boundary B>
class Relaxer {
 public:
  using Vec = std::array<double, D>;

  Relaxer(const Extent<D>& box, std::vector<double> radii, std::vector<Vec> x, int threads)
      : box_(box), r_(std::move(radii)), x_(std::move(x)), v_(r_.size()), f_(r_.size()), xref_(r_.size()),
        threads_(std::max(1, threads)) {}

  /// Relaxes at scale lambda until the largest relative overlap is below tol.
  /// Returns the FIRE steps used, or budget + 1 if it ran out.
  std::uint64_t relax(double lambda, double tol, std::uint64_t budget, double& max_rel) {
    lambda_ = lambda;
    for (auto& v : v_) v.fill(0.0);
    double dt_max = dt_max_, dt = 0.1 * dt_max, alpha = kFireAlpha0;
    int positive = 0;
    bool rebuild = needs_rebuild();
    for (std::uint64_t step = 0;; ++step) {
      if (rebuild) {
        build_list();
        dt_max = dt_max_;
        dt = std::min(dt, dt_max);
      }
      max_rel = forces();
      if (max_rel < tol) return step;
      if (step == budget) return budget + 1;
      double P = 0, vv = 0, ff = 0;
      for (std::size_t i = 0; i < r_.size(); ++i)
        for (int k = 0; k < D; ++k) {
          P += f_[i][k] * v_[i][k];
          vv += v_[i][k] * v_[i][k];
          ff += f_[i][k] * f_[i][k];
        }
      const bool uphill = !(P > 0);  // FIRE: stop (velocities to zero), else mix velocities towards the forces
      const double keep = 1 - alpha, mix = !uphill && ff > 0 ? alpha * std::sqrt(vv / ff) : 0.0;
      if (!uphill) {
        if (++positive > kFireNmin) {
          dt = std::min(dt * kFireFinc, dt_max);
          alpha *= kFireFalpha;
        }
      } else {
        dt *= kFireFdec;
        alpha = kFireAlpha0;
        positive = 0;
      }
      rebuild = advance(uphill, keep, mix, dt);
    }
  }

  int builds() const { return builds_; }
  const std::vector<Vec>& positions() const { return x_; }

 private:
  /// fn(i) for every sphere, on the threads when there are several.
  template <class Fn>
  void each_sphere(Fn&& fn) const {
    const auto n = static_cast<std::int64_t>(r_.size());
#if defined(_OPENMP)
    if (threads_ > 1) {
#pragma omp parallel for num_threads(threads_) schedule(static)
      for (std::int64_t i = 0; i < n; ++i) fn(static_cast<std::size_t>(i));
      return;
    }
#endif
    for (std::int64_t i = 0; i < n; ++i) fn(static_cast<std::size_t>(i));
  }

  /// Has sphere i moved or grown through its skin since the list was built?
  bool moved(std::size_t i) const {
    const double margin = built_lambda_ * r_[i] * (1 + kSkin) - lambda_ * r_[i];
    double d2 = 0;
    for (int k = 0; k < D; ++k) {
      double dx = x_[i][k] - xref_[i][k];
      if constexpr (B == Boundary::periodic) dx = min_image(dx, box_[k]);
      d2 += dx * dx;
    }
    return margin <= 0 || d2 >= margin * margin;
  }

  bool needs_rebuild() const {
    if (start_.empty()) return true;
    for (std::size_t i = 0; i < r_.size(); ++i)
      if (moved(i)) return true;
    return false;
  }

  /// One FIRE move of every sphere (velocities zeroed if uphill, else
  /// keep v + mix f; then v += dt f, x += dt v): one pass, on the threads.
  /// Returns whether the list must be rebuilt before the next forces.
  bool advance(bool uphill, double keep, double mix, double dt) {
    std::atomic<bool> any{false};
    each_sphere([&](std::size_t i) {
      for (int k = 0; k < D; ++k) {
        double v = uphill ? 0.0 : keep * v_[i][k] + mix * f_[i][k];
        v += dt * f_[i][k];
        v_[i][k] = v;
        double y = x_[i][k] + dt * v;
        if constexpr (B == Boundary::periodic) y = wrap(y, box_[k]);
        x_[i][k] = y;
      }
      if (moved(i)) any.store(true, std::memory_order_relaxed);
    });
    return any.load(std::memory_order_relaxed);
  }

  void build_list() {
    ++builds_;
    built_lambda_ = lambda_;
    const std::size_t n = r_.size();
    std::vector<Sphere<D>> s(n);
    for (std::size_t i = 0; i < n; ++i) {
      s[i].x = x_[i];
      if constexpr (B == Boundary::walls)
        for (int k = 0; k < D; ++k) s[i].x[k] = std::clamp(s[i].x[k], 0.0, box_[k]);
      s[i].r = lambda_ * r_[i] * (1 + kSkin);
      xref_[i] = x_[i];
    }
    neighbour_lists<D, B>(std::span<const Sphere<D>>(s), box_, start_, nbr_, threads_);  // sorted: see there
    // Stiffest sphere: sum of its pairs' stiffness 1/sigma^2 (an upper bound).
    std::vector<double> k(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      for (std::uint32_t m = start_[i]; m < start_[i + 1]; ++m) {
        const std::uint32_t j = nbr_[m];
        const double sig = lambda_ * (r_[i] + r_[j]);
        k[i] += 1 / (sig * sig);
        k[j] += 1 / (sig * sig);
      }
    double kmax = 0;
    for (std::size_t i = 0; i < n; ++i) kmax = std::max(kmax, k[i] + (B == Boundary::walls ? D / (lambda_ * lambda_ * r_[i] * r_[i]) : 0.0));
    dt_max_ = kmax > 0 ? 1.0 / std::sqrt(kmax) : 1.0;
    cut_ranges();
  }

  /// One range of spheres per thread, cut where the list pairs before the cut
  /// reach the thread's share; then, per sphere p, the pairs (i, p) whose i
  /// lies in an earlier range, in increasing i (cross_i_ from
  /// cross_start_[p]).
  void cut_ranges() {
    const std::size_t n = r_.size();
    const auto T = static_cast<std::size_t>(threads_);
    range_.assign(T + 1, static_cast<std::uint32_t>(n));
    range_[0] = 0;
    for (std::size_t b = 1; b < T; ++b) {
      const std::uint64_t share = static_cast<std::uint64_t>(start_[n]) * b / T;
      range_[b] = static_cast<std::uint32_t>(std::upper_bound(start_.begin(), start_.end(), share) - start_.begin() - 1);
      range_[b] = std::max(range_[b], range_[b - 1]);
    }
    cross_start_.assign(n + 1, 0);
    cross_i_.clear();
    if (T == 1) return;
    for (std::size_t b = 0; b < T; ++b)
      for (std::uint32_t i = range_[b]; i < range_[b + 1]; ++i)
        for (std::uint32_t m = start_[i]; m < start_[i + 1]; ++m)
          if (nbr_[m] >= range_[b + 1]) ++cross_start_[nbr_[m] + 1];
    for (std::size_t p = 0; p < n; ++p) cross_start_[p + 1] += cross_start_[p];
    cross_i_.resize(cross_start_[n]);
    std::vector<std::uint32_t> at(cross_start_.begin(), cross_start_.end() - 1);
    for (std::size_t b = 0; b < T; ++b)
      for (std::uint32_t i = range_[b]; i < range_[b + 1]; ++i)
        for (std::uint32_t m = start_[i]; m < start_[i + 1]; ++m)
          if (const std::uint32_t j = nbr_[m]; j >= range_[b + 1]) cross_i_[at[j]++] = i;
  }

  /// The pair (i, j), i < j, with xi = x_[i], ri = lambda_ r_[i]: false if
  /// they do not push each other; else the force c on j (-c on i). worst:
  /// raised to their relative overlap if they overlap.
  bool pair_force(const Vec& xi, double ri, std::uint32_t j, Vec& c, double& worst) const {
    const double sig = ri + lambda_ * r_[j];
    Vec dx;
    double d2 = 0;
    for (int k = 0; k < D; ++k) {
      dx[k] = x_[j][k] - xi[k];
      if constexpr (B == Boundary::periodic) dx[k] = min_image(dx[k], box_[k]);
      d2 += dx[k] * dx[k];
    }
    if (d2 >= sig * sig) return false;
    const double dist = std::sqrt(d2);
    const double rel = (sig - dist) / sig;
    worst = std::max(worst, rel);
    if (dist == 0) return false;
    const double mag = rel / sig / dist;  // force (delta/sigma)/sigma along the unit vector
    for (int k = 0; k < D; ++k) c[k] = mag * dx[k];
    return true;
  }

  /// Forces on the spheres of [lo, hi) (see the top of the file); returns
  /// the largest relative overlap among the pairs of their rows and walls.
  template <bool kRanges>
  double range_forces(std::uint32_t lo, std::uint32_t hi) {
    Vec c;
    double worst = 0, unused = 0;  // a cross pair's overlap counts in its row
    for (std::uint32_t p = lo; p < hi; ++p) {
      f_[p].fill(0.0);
      if constexpr (kRanges) {
        for (std::uint32_t x = cross_start_[p]; x < cross_start_[p + 1]; ++x) {
          const std::uint32_t i = cross_i_[x];
          if (pair_force(x_[i], lambda_ * r_[i], p, c, unused))
            for (int k = 0; k < D; ++k) f_[p][k] += c[k];
        }
      }
    }
    for (std::uint32_t i = lo; i < hi; ++i) {
      const Vec xi = x_[i];
      const double ri = lambda_ * r_[i];
      for (std::uint32_t m = start_[i]; m < start_[i + 1]; ++m) {
        const std::uint32_t j = nbr_[m];
        if (!pair_force(xi, ri, j, c, worst)) continue;
        for (int k = 0; k < D; ++k) f_[i][k] -= c[k];
        if (!kRanges || j < hi)
          for (int k = 0; k < D; ++k) f_[j][k] += c[k];
      }
      if constexpr (B == Boundary::walls) {
        for (int k = 0; k < D; ++k) {
          const double lo_gap = ri - xi[k], hi_gap = xi[k] + ri - box_[k];
          if (lo_gap > 0) {
            worst = std::max(worst, lo_gap / ri);
            f_[i][k] += lo_gap / (ri * ri);
          }
          if (hi_gap > 0) {
            worst = std::max(worst, hi_gap / ri);
            f_[i][k] -= hi_gap / (ri * ri);
          }
        }
      }
    }
    return worst;
  }

  /// Forces; returns the largest relative overlap.
  double forces() {
    const int T = threads_;
    if (T == 1) return range_forces<false>(0, static_cast<std::uint32_t>(r_.size()));
    double worst = 0;
#if defined(_OPENMP)
#pragma omp parallel for num_threads(T) schedule(static, 1) reduction(max : worst)
#endif
    for (int b = 0; b < T; ++b) worst = std::max(worst, range_forces<true>(range_[b], range_[b + 1]));
    return worst;
  }

  Extent<D> box_;
  std::vector<double> r_;
  std::vector<Vec> x_, v_, f_, xref_;
  std::vector<std::uint32_t> start_, nbr_;
  int threads_ = 1;
  std::vector<std::uint32_t> range_, cross_start_, cross_i_;
  double lambda_ = 1, built_lambda_ = 1, dt_max_ = 1;
  int builds_ = 0;
};

template <int D, Boundary B>
bool run(const std::array<double, 3>& box3, const std::vector<double>& radii, double scale0, int threads,
         std::vector<double>& pos, Progress& progress, RelaxStats& st) {
  const std::size_t n = radii.size();
  Extent<D> box;
  for (int k = 0; k < D; ++k) box[k] = box3[k];
  // Spatial order (row-major cells of about the mean spacing) for memory locality.
  const double cell = std::pow(box[0] * box[1] * (D == 3 ? box[D - 1] : 1.0) / static_cast<double>(n), 1.0 / D) * 2;
  std::vector<std::uint64_t> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t c = 0;
    for (int k = D - 1; k >= 0; --k)
      c = c * (static_cast<std::uint64_t>(box[k] / cell) + 2) + static_cast<std::uint64_t>(pos[i * D + k] / cell);
    key[i] = c;
  }
  std::vector<std::uint32_t> perm(n);
  std::iota(perm.begin(), perm.end(), 0u);
  std::sort(perm.begin(), perm.end(), [&](auto a, auto b) { return key[a] != key[b] ? key[a] < key[b] : a < b; });
  key.clear();
  key.shrink_to_fit();
  std::vector<double> r(n);
  std::vector<std::array<double, D>> x(n);
  for (std::size_t m = 0; m < n; ++m) {
    r[m] = radii[perm[m]];
    for (int k = 0; k < D; ++k) x[m][k] = pos[perm[m] * D + k];
  }
  Relaxer<D, B> relaxer(box, std::move(r), std::move(x), threads);
  double lambda = scale0;
  const double total = std::log(1 / scale0);
  bool ok = true;
  while (true) {
    const bool last = lambda >= 1;
    double worst = 0;
    const std::uint64_t used = relaxer.relax(lambda, last ? kFinalOverlapTol : kStepOverlapTol,
                                             std::min(kFireStepsPerGrowth, kFireStepsTotal - st.fire_steps), worst);
    st.max_rel_overlap = worst;
    if (used > kFireStepsPerGrowth || st.fire_steps + used > kFireStepsTotal) {
      st.fire_steps += std::min(used, kFireStepsPerGrowth);
      ok = false;
      break;
    }
    st.fire_steps += used;
    char buf[160];
    std::snprintf(buf, sizeof buf, "scale %.4f, max rel. overlap %.1e, %llu FIRE steps, %d list builds", lambda,
                  worst, static_cast<unsigned long long>(st.fire_steps), relaxer.builds());
    progress.update(total > 0 ? 1 - std::log(1 / lambda) / total : 1.0, buf);
    if (last) break;
    lambda = std::min(1.0, lambda * kGrowthStep);
    ++st.growth_steps;
  }
  st.list_builds = relaxer.builds();
  const auto& y = relaxer.positions();
  for (std::size_t m = 0; m < n; ++m)
    for (int k = 0; k < D; ++k) pos[perm[m] * D + k] = y[m][k];
  return ok;
}

}  // namespace

bool grow_and_relax(int d, Boundary b, const std::array<double, 3>& box, const std::vector<double>& radii,
                    double scale0, int threads, std::vector<double>& pos, Progress& progress, RelaxStats& stats) {
  if (d == 2)
    return b == Boundary::walls ? run<2, Boundary::walls>(box, radii, scale0, threads, pos, progress, stats)
                                : run<2, Boundary::periodic>(box, radii, scale0, threads, pos, progress, stats);
  return b == Boundary::walls ? run<3, Boundary::walls>(box, radii, scale0, threads, pos, progress, stats)
                              : run<3, Boundary::periodic>(box, radii, scale0, threads, pos, progress, stats);
}

}  // namespace hgrid::detail
