// Growth + FIRE. Energy E = 1/2 sum_pairs (delta_ij / sigma_ij)^2 with delta
// the overlap and sigma = r_i + r_j: the relative overlaps, which is also the
// convergence criterion. Unit masses; a pair's stiffness 1/sigma^2 makes a big
// sphere with many small neighbours no stiffer than a small one, so one time
// step suits all. Contacts come from a Verlet list (skin kSkin r_i) built with
// the HGrid and rebuilt only when a sphere has moved or grown through its skin;
// its partner lists are sorted, so the packing does not depend on the grid.
#include "packing/detail/gen_relax.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "packing/detail/gen_pairs.hpp"

namespace hgrid::detail {
namespace {

// FIRE parameters (Bitzek et al. 2006, their recommended values).
constexpr int kFireNmin = 5;
constexpr double kFireFinc = 1.1, kFireFdec = 0.5, kFireAlpha0 = 0.1, kFireFalpha = 0.99;

template <int D, Boundary B>
class Relaxer {
 public:
  using Vec = std::array<double, D>;

  Relaxer(const Extent<D>& box, std::vector<double> radii, std::vector<Vec> x)
      : box_(box), r_(std::move(radii)), x_(std::move(x)), v_(r_.size()), f_(r_.size()), xref_(r_.size()) {}

  /// Relaxes at scale lambda until the largest relative overlap is below tol.
  /// Returns the FIRE steps used, or budget + 1 if it ran out.
  std::uint64_t relax(double lambda, double tol, std::uint64_t budget, double& max_rel) {
    lambda_ = lambda;
    for (auto& v : v_) v.fill(0.0);
    double dt_max = dt_max_, dt = 0.1 * dt_max, alpha = kFireAlpha0;
    int positive = 0;
    for (std::uint64_t step = 0;; ++step) {
      if (needs_rebuild()) {
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
      if (P > 0) {
        const double mix = ff > 0 ? alpha * std::sqrt(vv / ff) : 0.0;
        for (std::size_t i = 0; i < r_.size(); ++i)
          for (int k = 0; k < D; ++k) v_[i][k] = (1 - alpha) * v_[i][k] + mix * f_[i][k];
        if (++positive > kFireNmin) {
          dt = std::min(dt * kFireFinc, dt_max);
          alpha *= kFireFalpha;
        }
      } else {
        for (auto& v : v_) v.fill(0.0);
        dt *= kFireFdec;
        alpha = kFireAlpha0;
        positive = 0;
      }
      for (std::size_t i = 0; i < r_.size(); ++i)
        for (int k = 0; k < D; ++k) {
          v_[i][k] += dt * f_[i][k];
          double y = x_[i][k] + dt * v_[i][k];
          if constexpr (B == Boundary::periodic) y = wrap(y, box_[k]);
          x_[i][k] = y;
        }
    }
  }

  int builds() const { return builds_; }
  const std::vector<Vec>& positions() const { return x_; }

 private:
  bool needs_rebuild() const {
    if (start_.empty()) return true;
    for (std::size_t i = 0; i < r_.size(); ++i) {
      const double margin = built_lambda_ * r_[i] * (1 + kSkin) - lambda_ * r_[i];
      if (margin <= 0) return true;
      double d2 = 0;
      for (int k = 0; k < D; ++k) {
        double dx = x_[i][k] - xref_[i][k];
        if constexpr (B == Boundary::periodic) dx = min_image(dx, box_[k]);
        d2 += dx * dx;
      }
      if (d2 >= margin * margin) return true;
    }
    return false;
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
    neighbour_lists<D, B>(std::span<const Sphere<D>>(s), box_, start_, nbr_);  // sorted: see there
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
  }

  /// Forces; returns the largest relative overlap.
  double forces() {
    for (auto& f : f_) f.fill(0.0);
    double worst = 0;
    const std::size_t n = r_.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec xi = x_[i];
      const double ri = lambda_ * r_[i];
      for (std::uint32_t m = start_[i]; m < start_[i + 1]; ++m) {
        const std::uint32_t j = nbr_[m];
        const double sig = ri + lambda_ * r_[j];
        Vec dx;
        double d2 = 0;
        for (int k = 0; k < D; ++k) {
          dx[k] = x_[j][k] - xi[k];
          if constexpr (B == Boundary::periodic) dx[k] = min_image(dx[k], box_[k]);
          d2 += dx[k] * dx[k];
        }
        if (d2 >= sig * sig) continue;
        const double dist = std::sqrt(d2);
        const double rel = (sig - dist) / sig;
        worst = std::max(worst, rel);
        if (dist == 0) continue;
        const double mag = rel / sig / dist;  // force (delta/sigma)/sigma along the unit vector
        for (int k = 0; k < D; ++k) {
          f_[i][k] -= mag * dx[k];
          f_[j][k] += mag * dx[k];
        }
      }
      if constexpr (B == Boundary::walls) {
        for (int k = 0; k < D; ++k) {
          const double lo = ri - xi[k], hi = xi[k] + ri - box_[k];
          if (lo > 0) {
            worst = std::max(worst, lo / ri);
            f_[i][k] += lo / (ri * ri);
          }
          if (hi > 0) {
            worst = std::max(worst, hi / ri);
            f_[i][k] -= hi / (ri * ri);
          }
        }
      }
    }
    return worst;
  }

  Extent<D> box_;
  std::vector<double> r_;
  std::vector<Vec> x_, v_, f_, xref_;
  std::vector<std::uint32_t> start_, nbr_;
  double lambda_ = 1, built_lambda_ = 1, dt_max_ = 1;
  int builds_ = 0;
};

template <int D, Boundary B>
bool run(const std::array<double, 3>& box3, const std::vector<double>& radii, double scale0, std::vector<double>& pos,
         Progress& progress, RelaxStats& st) {
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
  Relaxer<D, B> relaxer(box, std::move(r), std::move(x));
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
                    double scale0, std::vector<double>& pos, Progress& progress, RelaxStats& stats) {
  if (d == 2)
    return b == Boundary::walls ? run<2, Boundary::walls>(box, radii, scale0, pos, progress, stats)
                                : run<2, Boundary::periodic>(box, radii, scale0, pos, progress, stats);
  return b == Boundary::walls ? run<3, Boundary::walls>(box, radii, scale0, pos, progress, stats)
                              : run<3, Boundary::periodic>(box, radii, scale0, pos, progress, stats);
}

}  // namespace hgrid::detail
