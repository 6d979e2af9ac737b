// Growth + FIRE. Energy E = 1/2 sum_pairs (delta_ij / sigma_ij)^2 with delta
// the overlap and sigma = r_i + r_j: the relative overlaps, which is also the
// convergence criterion. A pair's stiffness 1/sigma^2 makes a big sphere with
// many small neighbours about as stiff as a small one, but the spheres'
// stiffness sums still span a factor ~50; each sphere's mass is its sum
// (kFireMassFloor), so one time step suits all. Contacts come from a Verlet
// list (skin kSkin r_i), rebuilt only when a sphere has moved or grown
// through its own skin; the list is built by the contact list
// (contacts/contact_list.hpp, the spheres inflated by kSkin r_i, as exact
// pairs), so its rows are in canonical order and the packing does not
// depend on the grid. The rule stays this file's, one margin per sphere
// (the contact list's two-smallest-margins rule would rebuild less often,
// and the masses, set at each build, and so every packing would change).
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
#include <span>

#include "hgridlab/contacts/contact_list.hpp"

namespace hgrid::detail {
namespace {

// FIRE parameters (Bitzek et al. 2006, their recommended values).
constexpr int kFireNmin = 5;
constexpr double kFireFinc = 1.1, kFireFdec = 0.5, kFireAlpha0 = 0.1, kFireFalpha = 0.99;
// Largest time step: one, as the masses (kFireMassFloor) make every sphere's
// period about one time unit.
constexpr double kFireDtMax = 1.0;

template <int D, Boundary B>
class Relaxer {
 public:
  using Vec = std::array<double, D>;

  Relaxer(const Extent<D>& box, std::vector<double> radii, std::vector<Vec> x, int threads)
      : box_(box), r_(std::move(radii)), rs_(r_.size()), skin2_(r_.size()), x_(std::move(x)), v_(r_.size()),
        f_(r_.size()), xref_(r_.size()), threads_(std::max(1, threads)), list_(list_box(box), list_params(threads_)) {}

  /// Relaxes at scale lambda until the largest relative overlap is below tol.
  /// Returns the FIRE steps used, or budget + 1 if it ran out.
  std::uint64_t relax(double lambda, double tol, std::uint64_t budget, double& max_rel) {
    return fire_until(lambda, budget, [&](double worst) {
      max_rel = worst;
      return worst < tol;
    });
  }

  /// FIRE at full size with a weight w_i on every sphere along -x_d (walls
  /// only), until the net forces' root mean square is below kSettleForceTol
  /// of the weights'. Returns the FIRE steps used, or budget + 1 if it ran out.
  std::uint64_t settle(const std::vector<double>& weights, std::uint64_t budget) {
    weight_ = weights.data();
    double w2 = 0;
    for (const double w : weights) w2 += w * w;
    const std::uint64_t used = fire_until(1.0, budget, [&](double) {
      double f2 = 0;
      for (const Vec& f : f_)
        for (int k = 0; k < D; ++k) f2 += f[k] * f[k];
      return std::sqrt(f2 / w2) < kSettleForceTol;
    });
    weight_ = nullptr;
    return used;
  }

  int builds() const { return builds_; }
  const std::vector<Vec>& positions() const { return x_; }

 private:
  /// FIRE's sums over the spheres: power f.v and the squared norms in the
  /// mass metric, v.m.v and f.m^-1.f (FIRE on the coordinates sqrt(m) x,
  /// where every mass is one).
  struct Sums {
    double P = 0, vv = 0, ff = 0;
  };
  /// FIRE's state: time step, mixing, steps since the power was last <= 0.
  struct Fire {
    double dt = 0.1 * kFireDtMax, alpha = kFireAlpha0;
    int positive = 0;
  };

  /// FIRE at scale lambda from rest until done(the largest relative
  /// overlap) says so after a step's forces. Returns the FIRE steps used,
  /// or budget + 1 if it ran out.
  template <class Done>
  std::uint64_t fire_until(double lambda, std::uint64_t budget, Done&& done) {
    lambda_ = lambda;
    for (std::size_t i = 0; i < r_.size(); ++i) rs_[i] = lambda_ * r_[i];
    set_margins();
    for (auto& v : v_) v.fill(0.0);
    Fire fire;
    bool rebuild = needs_rebuild();
    for (std::uint64_t step = 0;; ++step) {
      if (rebuild) build_list();
      Sums sums;
      if (done(forces(sums))) return step;
      if (step == budget) return budget + 1;
      rebuild = fire_move(fire, sums);
    }
  }

  /// One FIRE step from the forces' sums: the velocities stopped (uphill)
  /// or mixed towards the forces, dt and alpha adapted, then the move.
  /// Returns whether the list must be rebuilt before the next forces.
  bool fire_move(Fire& s, const Sums& sums) {
    const double P = sums.P, vv = sums.vv, ff = sums.ff;
    const bool uphill = !(P > 0);  // FIRE: stop (velocities to zero), else mix velocities towards the forces
    const double keep = 1 - s.alpha, mix = !uphill && ff > 0 ? s.alpha * std::sqrt(vv / ff) : 0.0;
    if (!uphill) {
      if (++s.positive > kFireNmin) {
        s.dt = std::min(s.dt * kFireFinc, kFireDtMax);
        s.alpha *= kFireFalpha;
      }
    } else {
      s.dt *= kFireFdec;
      s.alpha = kFireAlpha0;
      s.positive = 0;
    }
    return advance(uphill, keep, mix, s.dt);
  }

  /// Adds sphere i's terms to the sums (in the one order every thread count uses:
  /// spheres in increasing i, axes in increasing k).
  void add_sums(std::size_t i, Sums& s) const {
    const double w = w_[i];
    for (int k = 0; k < D; ++k) {
      s.P += f_[i][k] * v_[i][k];
      s.vv += v_[i][k] * v_[i][k] / w;
      s.ff += w * f_[i][k] * f_[i][k];
    }
  }

  /// skin2_[i]: how far sphere i may move from where the list saw it before
  /// it must be rebuilt, squared; -1 when its growth alone has used up its
  /// skin (margin = built r (1 + kSkin) - lambda r <= 0). Set whenever lambda_
  /// or built_lambda_ changes.
  void set_margins() {
    for (std::size_t i = 0; i < r_.size(); ++i) {
      const double margin = built_lambda_ * r_[i] * (1 + kSkin) - lambda_ * r_[i];
      skin2_[i] = margin <= 0 ? -1.0 : margin * margin;
    }
  }

  /// Has a sphere at x (at xref when the list was built) moved or grown
  /// through its skin (squared margin skin2)?
  static bool moved(const Vec& x, const Vec& xref, double skin2, const Extent<D>& box) {
    double d2 = 0;
    for (int k = 0; k < D; ++k) {
      double dx = x[k] - xref[k];
      if constexpr (B == Boundary::periodic) dx = min_image(dx, box[k]);
      d2 += dx * dx;
    }
    return d2 >= skin2;
  }

  bool needs_rebuild() const {
    if (start_.empty()) return true;
    for (std::size_t i = 0; i < r_.size(); ++i)
      if (moved(x_[i], xref_[i], skin2_[i], box_)) return true;
    return false;
  }

  /// One FIRE move of every sphere (velocities zeroed if uphill, else
  /// keep v + mix f / m; then v += dt f / m, x += dt v): one pass, on the threads.
  /// Returns whether the list must be rebuilt before the next forces.
  bool advance(bool uphill, double keep, double mix, double dt) {
    // What the loop reads besides the arrays it writes, in locals: the
    // stores to v_ and x_ could alias members, which would then be reloaded
    // for every sphere (measured: a third of a FIRE step went to this pass).
    const Extent<D> box = box_;
    const double* const skin2 = skin2_.data();
    const Vec* const f = f_.data();
    const double* const w = w_.data();
    const Vec* const xref = xref_.data();
    Vec* const v = v_.data();
    Vec* const x = x_.data();
    const auto n = static_cast<std::int64_t>(r_.size());
    bool any = false;  // a sphere through its skin; once one is, the others need not be checked
#if defined(_OPENMP)
#pragma omp parallel for num_threads(threads_) schedule(static) reduction(|| : any) if (threads_ > 1)
#endif
    for (std::int64_t s = 0; s < n; ++s) {
      const auto i = static_cast<std::size_t>(s);
      for (int k = 0; k < D; ++k) {
        const double wf = w[i] * f[i][k];
        double vk = uphill ? 0.0 : keep * v[i][k] + mix * wf;
        vk += dt * wf;
        v[i][k] = vk;
        double y = x[i][k] + dt * vk;
        if constexpr (B == Boundary::periodic) y = wrap(y, box[k]);
        x[i][k] = y;
      }
      if (!any) any = moved(x[i], xref[i], skin2[i], box);
    }
    return any;
  }

  /// The contact list's box: this one's sides, every axis periodic or walled.
  static ListBox<D> list_box(const Extent<D>& box) {
    ListBox<D> b;
    b.side = box;
    b.periodic.fill(B == Boundary::periodic);
    return b;
  }
  /// No skin: at every update the list's pairs are those of the spheres it
  /// is given (here inflated by kSkin), from a grid rebuilt in place.
  static ContactListParams list_params(int threads) {
    ContactListParams p;
    p.threads = threads;
    return p;
  }

  void build_list() {
    ++builds_;
    built_lambda_ = lambda_;
    set_margins();
    const std::size_t n = r_.size();
    inflated_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      Sphere<D>& s = inflated_[i];
      s.x = x_[i];
      if constexpr (B == Boundary::walls)
        for (int k = 0; k < D; ++k) s.x[k] = std::clamp(s.x[k], 0.0, box_[k]);
      s.r = rs_[i] * (1 + kSkin);  // lambda_ r_[i] (1 + kSkin), as rs_ holds lambda_ r_[i]
      xref_[i] = x_[i];
    }
    list_.update(std::span<const Sphere<D>>(inflated_));  // canonical rows: see there
    start_ = list_.start();
    nbr_ = list_.partners();
    // Each sphere's stiffness: the sum of its list pairs' 1/sigma^2 (an upper
    // bound on its touching pairs') and its walls'.
    std::vector<double> k(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      for (std::uint32_t m = start_[i]; m < start_[i + 1]; ++m) {
        const std::uint32_t j = nbr_[m];
        const double sig = lambda_ * (r_[i] + r_[j]);
        k[i] += 1 / (sig * sig);
        k[j] += 1 / (sig * sig);
      }
    double kmax = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if constexpr (B == Boundary::walls) k[i] += D / (lambda_ * lambda_ * r_[i] * r_[i]);
      kmax = std::max(kmax, k[i]);
    }
    // Masses: each sphere's stiffness, at least kFireMassFloor of the
    // stiffest's (see there), so that every sphere's natural period is about
    // one time unit and kFireDtMax is stable.
    w_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double m = std::max(k[i], kFireMassFloor * kmax);
      w_[i] = m > 0 ? 1.0 / m : 1.0;
    }
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

  /// What the force loop reads, copied into a local: the stores to the
  /// forces could otherwise alias members, and every pair would reload them.
  struct View {
    const Vec* x;
    const double* rs;  // radii at the current scale
    Extent<D> box, half;  // half: box / 2, min_image's bound
  };

  View view() const {
    View w{x_.data(), rs_.data(), box_, box_};
    for (int k = 0; k < D; ++k) w.half[k] = 0.5 * box_[k];
    return w;
  }

  /// The pair (i, j), i < j, with xi = x[i], ri = rs[i]: false if
  /// they do not push each other; else the force c on j (-c on i). worst:
  /// raised to their relative overlap if they overlap.
  static bool pair_force(const View& w, const Vec& xi, double ri, std::uint32_t j, Vec& c, double& worst) {
    const double sig = ri + w.rs[j];
    Vec dx;
    double d2 = 0;
    for (int k = 0; k < D; ++k) {
      dx[k] = w.x[j][k] - xi[k];
      if constexpr (B == Boundary::periodic) {  // min_image(), its bound precomputed
        if (dx[k] > w.half[k])
          dx[k] -= w.box[k];
        else if (dx[k] < -w.half[k])
          dx[k] += w.box[k];
      }
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
  /// One thread (!kRanges) also adds each sphere to `sums` as soon as its
  /// force is complete (after its row: later rows only add to later
  /// spheres), so the sums' serial chain of additions overlaps the pair work
  /// instead of making a pass of its own; the order is the same.
  template <bool kRanges>
  double range_forces(std::uint32_t lo, std::uint32_t hi, Sums* sums = nullptr) {
    const View w = view();
    Vec* const f = f_.data();
    const std::uint32_t* const start = start_.data();
    const std::uint32_t* const nbr = nbr_.data();
    Vec c;
    double worst = 0, unused = 0;  // a cross pair's overlap counts in its row
    for (std::uint32_t p = lo; p < hi; ++p) {
      f[p].fill(0.0);
      if constexpr (kRanges) {
        for (std::uint32_t x = cross_start_[p]; x < cross_start_[p + 1]; ++x) {
          const std::uint32_t i = cross_i_[x];
          if (pair_force(w, w.x[i], w.rs[i], p, c, unused))
            for (int k = 0; k < D; ++k) f[p][k] += c[k];
        }
      }
    }
    for (std::uint32_t i = lo; i < hi; ++i) {
      const Vec xi = w.x[i];
      const double ri = w.rs[i];
      Vec fi = f[i];  // its row alone changes it from here on: the same additions, in a register
      for (std::uint32_t m = start[i]; m < start[i + 1]; ++m) {
        const std::uint32_t j = nbr[m];
        if (!pair_force(w, xi, ri, j, c, worst)) continue;
        for (int k = 0; k < D; ++k) fi[k] -= c[k];
        if (!kRanges || j < hi)
          for (int k = 0; k < D; ++k) f[j][k] += c[k];
      }
      if constexpr (B == Boundary::walls) {
        if (weight_) fi[D - 1] -= weight_[i];  // settling under gravity (settle_under_gravity)
        for (int k = 0; k < D; ++k) {
          const double lo_gap = ri - xi[k], hi_gap = xi[k] + ri - w.box[k];
          if (lo_gap > 0) {
            worst = std::max(worst, lo_gap / ri);
            fi[k] += lo_gap / (ri * ri);
          }
          if (hi_gap > 0) {
            worst = std::max(worst, hi_gap / ri);
            fi[k] -= hi_gap / (ri * ri);
          }
        }
      }
      f[i] = fi;
      if constexpr (!kRanges) add_sums(i, *sums);
    }
    return worst;
  }

  /// Forces and FIRE's sums; returns the largest relative overlap.
  double forces(Sums& sums) {
    const int T = threads_;
    if (T == 1) return range_forces<false>(0, static_cast<std::uint32_t>(r_.size()), &sums);
    double worst = 0;
#if defined(_OPENMP)
#pragma omp parallel for num_threads(T) schedule(static, 1) reduction(max : worst)
#endif
    for (int b = 0; b < T; ++b) worst = std::max(worst, range_forces<true>(range_[b], range_[b + 1]));
    for (std::size_t i = 0; i < r_.size(); ++i) add_sums(i, sums);
    return worst;
  }

  Extent<D> box_;
  std::vector<double> w_;  // inverse masses, set with the list
  std::vector<double> r_, rs_, skin2_;  // radii; at the current scale; squared skin margins
  std::vector<Vec> x_, v_, f_, xref_;
  std::span<const std::uint32_t> start_, nbr_;  // the Verlet list: list_'s rows, valid until its next update
  int threads_ = 1;
  ContactList<D> list_;              // builds the Verlet list
  std::vector<Sphere<D>> inflated_;  // the spheres it is built from
  std::vector<std::uint32_t> range_, cross_start_, cross_i_;
  double lambda_ = 1, built_lambda_ = 1;
  int builds_ = 0;
  const double* weight_ = nullptr;  // weights along -x_d while settling
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

template <int D>
bool run_settle(const std::array<double, 3>& box3, const std::vector<double>& radii, int threads,
                std::vector<double>& pos, Progress& progress, RelaxStats& st) {
  const std::size_t n = radii.size();
  Extent<D> box;
  for (int k = 0; k < D; ++k) box[k] = box3[k];
  std::vector<std::array<double, D>> x(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < D; ++k) x[i][k] = pos[i * D + k];
  // Weights in proportion to the volumes, scaled so that the floor's
  // pressure, P = sum w / floor area, would overlap a largest sphere resting
  // on it by about kSettleOverlap: relative overlap ~ P (2 r_max)^d.
  const double rmax = *std::max_element(radii.begin(), radii.end());
  double floor_area = 1, sum = 0;
  for (int k = 0; k + 1 < D; ++k) floor_area *= box[k];
  std::vector<double> w(n);
  for (std::size_t i = 0; i < n; ++i) sum += w[i] = std::pow(radii[i] / rmax, D);
  const double g = kSettleOverlap / (sum / floor_area * std::pow(2 * rmax, D));
  for (auto& v : w) v *= g;
  Relaxer<D, Boundary::walls> relaxer(box, radii, std::move(x), threads);
  progress.update(0.0, "settling under gravity");
  const std::uint64_t used = relaxer.settle(w, kSettleSteps);
  st.fire_steps += std::min(used, kSettleSteps);
  if (used > kSettleSteps) return false;
  progress.update(0.5, "settled; relaxing the overlaps without gravity");
  double worst = 0;
  const std::uint64_t more = relaxer.relax(1.0, kFinalOverlapTol, kFireStepsPerGrowth, worst);
  st.fire_steps += std::min(more, kFireStepsPerGrowth);
  st.max_rel_overlap = worst;
  st.list_builds = relaxer.builds();
  if (more > kFireStepsPerGrowth) return false;
  const auto& y = relaxer.positions();
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < D; ++k) pos[i * D + k] = y[i][k];
  progress.update(1.0, "settled");
  return true;
}

}  // namespace

bool settle_under_gravity(int d, const std::array<double, 3>& box, const std::vector<double>& radii, int threads,
                          std::vector<double>& pos, Progress& progress, RelaxStats& stats) {
  return d == 2 ? run_settle<2>(box, radii, threads, pos, progress, stats)
                : run_settle<3>(box, radii, threads, pos, progress, stats);
}

bool grow_and_relax(int d, Boundary b, const std::array<double, 3>& box, const std::vector<double>& radii,
                    double scale0, int threads, std::vector<double>& pos, Progress& progress, RelaxStats& stats) {
  if (d == 2)
    return b == Boundary::walls ? run<2, Boundary::walls>(box, radii, scale0, threads, pos, progress, stats)
                                : run<2, Boundary::periodic>(box, radii, scale0, threads, pos, progress, stats);
  return b == Boundary::walls ? run<3, Boundary::walls>(box, radii, scale0, threads, pos, progress, stats)
                              : run<3, Boundary::periodic>(box, radii, scale0, threads, pos, progress, stats);
}

}  // namespace hgrid::detail
