// A dense hard-sphere fluid moved by Monte Carlo sweeps (3D, periodic,
// alpha = -3, omega = 10, nu = 0.55; the generator's compressed packing,
// then one sweep of displacement moves per step, each particle once in
// random order, the step size set for ~40 % acceptance; the generator's own
// moves also swap radii, which would force a rebuild at every step): the
// contact detection of every step, exact
// (pairs with distance < r_i + r_j: none in a hard-sphere fluid, so the
// work is the candidates'), timed three ways on one thread over the same
// recorded trajectory:
//   - the grid rebuilt every step, with the fastest of the paper's sizes for
//     nu = 0.1 ... 0.7 and the linked cell (the baseline);
//   - the contact list at every skin of a scan;
//   - the contact list at the skin model's choice (advice/skin_model.hpp),
//     given what the list measured at two reference skins only.
// At every 25th step the list's pairs are compared with a fresh grid's.
// The trajectory is recorded first (not timed); each timed pass replays it,
// the passes alternated over --rounds rounds, the fastest kept.
//   build/skin_scan_mc [--n 4000] [--steps 100] [--rounds 3] [--reference 0.2]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "hgridlab/advice/skin_model.hpp"
#include "hgridlab/advice/skin_tuner.hpp"
#include "hgridlab/base/clock.hpp"
#include "hgridlab/contacts/contact_list.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/packing/generate.hpp"

#include "detail/skin_measurement.hpp"

using namespace hgrid;
using bench::ListRun;

namespace {

constexpr double kNu = 0.55, kOmega = 10, kAlpha = -3;
constexpr int kCheckEvery = 25;

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

std::vector<Sphere<3>> spheres_of(const std::vector<double>& x, const std::vector<double>& r) {
  std::vector<Sphere<3>> s(r.size());
  for (std::size_t i = 0; i < r.size(); ++i) s[i] = {{x[3 * i], x[3 * i + 1], x[3 * i + 2]}, r[i]};
  return s;
}

Pairs fresh_pairs(const std::vector<Sphere<3>>& s, const Extent<3>& box, const std::vector<double>& sizes) {
  HGrid<3, Boundary::periodic> g(s, box, GridParams{sizes, Search::bottom_up});
  Pairs out;
  g.for_each_pair([&](std::uint32_t i, std::uint32_t j) { out.emplace_back(std::min(i, j), std::max(i, j)); });
  std::sort(out.begin(), out.end());
  return out;
}

/// Hard-sphere Metropolis displacement sweeps on a linked cell (cells of at
/// least 2 r_max, kept up to date move by move): the trajectory's maker, not
/// timed.
class Sweeper {
 public:
  Sweeper(std::vector<double> x, std::vector<double> r, const Extent<3>& box, std::uint64_t seed)
      : x_(std::move(x)), r_(std::move(r)), box_(box), rng_(seed) {
    const double rmax = *std::max_element(r_.begin(), r_.end());
    for (int k = 0; k < 3; ++k) n_[k] = std::max(1, int(std::floor(box[k] / (2 * rmax))));
    cells_.assign(std::size_t(n_[0]) * n_[1] * n_[2], {});
    cell_of_.resize(r_.size());
    for (std::size_t i = 0; i < r_.size(); ++i) cells_[cell_of_[i] = cell(&x_[3 * i])].push_back(i);
    step_ = 0.1 * *std::min_element(r_.begin(), r_.end());
  }
  const std::vector<double>& positions() const { return x_; }
  /// One sweep; returns the fraction of moves accepted.
  double sweep() {
    std::vector<std::size_t> order(r_.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng_);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::size_t accepted = 0;
    for (std::size_t i : order) {
      double y[3];
      for (int k = 0; k < 3; ++k) {
        y[k] = x_[3 * i + k] + step_ * u(rng_);
        y[k] -= box_[k] * std::floor(y[k] / box_[k]);
      }
      if (overlaps(i, y)) continue;
      ++accepted;
      const std::size_t c = cell(y);
      for (int k = 0; k < 3; ++k) x_[3 * i + k] = y[k];
      if (c != cell_of_[i]) {
        auto& from = cells_[cell_of_[i]];
        from.erase(std::find(from.begin(), from.end(), i));
        cells_[cell_of_[i] = c].push_back(i);
      }
    }
    const double rate = double(accepted) / double(r_.size());
    step_ *= rate > 0.4 ? 1.05 : 0.95;  // towards ~40 % acceptance
    return rate;
  }

 private:
  std::size_t cell(const double* y) const {
    std::size_t c = 0;
    for (int k = 2; k >= 0; --k) c = c * n_[k] + std::min(n_[k] - 1, int(y[k] / box_[k] * n_[k]));
    return c;
  }
  bool overlaps(std::size_t i, const double* y) const {
    int c[3];
    for (int k = 0; k < 3; ++k) c[k] = std::min(n_[k] - 1, int(y[k] / box_[k] * n_[k]));
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        for (int e = -1; e <= 1; ++e) {
          if ((n_[0] < 3 && a == 1) || (n_[1] < 3 && b == 1) || (n_[2] < 3 && e == 1)) continue;  // visited once
          const int q[3] = {(c[0] + a + n_[0]) % n_[0], (c[1] + b + n_[1]) % n_[1], (c[2] + e + n_[2]) % n_[2]};
          for (std::size_t j : cells_[(std::size_t(q[2]) * n_[1] + q[1]) * n_[0] + q[0]]) {
            if (j == i) continue;
            double d2 = 0;
            for (int k = 0; k < 3; ++k) {
              double d = y[k] - x_[3 * j + k];
              d -= box_[k] * std::nearbyint(d / box_[k]);
              d2 += d * d;
            }
            const double s = r_[i] + r_[j];
            if (d2 < s * s) return true;
          }
        }
    return false;
  }
  std::vector<double> x_, r_;
  Extent<3> box_;
  std::mt19937_64 rng_;
  int n_[3] = {1, 1, 1};
  std::vector<std::vector<std::size_t>> cells_;
  std::vector<std::size_t> cell_of_;
  double step_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t n = 4000, steps = 100, rounds = 3;
  double reference = 0.2;
  for (int a = 1; a + 1 < argc; a += 2) {
    if (!std::strcmp(argv[a], "--n")) n = std::strtoull(argv[a + 1], nullptr, 10);
    else if (!std::strcmp(argv[a], "--steps")) steps = std::strtoull(argv[a + 1], nullptr, 10);
    else if (!std::strcmp(argv[a], "--rounds")) rounds = std::strtoull(argv[a + 1], nullptr, 10);
    else if (!std::strcmp(argv[a], "--reference")) reference = std::atof(argv[a + 1]);
  }
  // The trajectory: the compressed packing (growth + FIRE), then one sweep
  // of displacement moves per step.
  PackingSpec spec{.d = 3, .n = n, .nu = kNu, .alpha = kAlpha, .omega = kOmega, .boundary = Boundary::periodic,
                   .placement = Placement::excluded, .seed = 1, .progress = false};
  spec.method = ExcludedMethod::growth;
  spec.threads = 1;
  const Packing p = generate_packing(spec);
  const std::vector<double> radii = p.radii;
  const Extent<3> box{p.box[0], p.box[1], p.box[2]};
  Sweeper mc(p.positions, radii, box, /*seed=*/2);
  std::vector<std::vector<double>> frames;
  double acceptance = 0;
  for (std::uint64_t t = 0; t < steps; ++t) {
    acceptance += mc.sweep() / double(steps);
    frames.push_back(mc.positions());
  }
  const ListBox<3> lbox{{p.box[0], p.box[1], p.box[2]}, {0, 0, 0}, {true, true, true}};
  const Empirical dist(radii);
  const double r_min = dist.r_min();

  // The baseline: the grid rebuilt every step, the fastest of the scanned sizes.
  std::map<std::string, std::vector<double>> sized = bench::scanned_sizes(dist);
  const auto rebuild_pass = [&](const std::vector<double>& sizes) {
    std::vector<Sphere<3>> s = spheres_of(frames[0], radii);
    HGrid<3, Boundary::periodic> g(s, box, GridParams{sizes, Search::bottom_up});
    std::uint64_t contacts = 0;
    const auto t0 = Clock::now();
    for (const auto& x : frames) {
      for (std::size_t i = 0; i < s.size(); ++i) s[i].x = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
      g.rebuild(s);
      g.for_each_pair<PairsOnly>([&](std::uint32_t, std::uint32_t) { ++contacts; });
    }
    return std::make_pair(seconds_since(t0) / double(frames.size()), contacts);
  };
  const std::vector<double> list_sizes = sized["nu=0.5"];
  std::uint64_t mismatches = 0;
  const auto list_pass = [&](double skin, bool check) {
    ContactList<3> list(lbox, ContactListParams{list_sizes, Search::bottom_up, 1, skin, 0.0});
    ListRun r;
    double seconds = 0;
    for (std::size_t t = 0; t < frames.size(); ++t) {
      const auto t0 = Clock::now();
      list.update(frames[t], radii);
      list.for_each_contact([&](std::uint32_t, std::uint32_t) { ++r.contacts; });
      seconds += seconds_since(t0);
      if (check && t % kCheckEvery == 0) {
        Pairs got;
        list.for_each_contact([&](std::uint32_t i, std::uint32_t j) { got.emplace_back(i, j); });
        std::sort(got.begin(), got.end());
        mismatches += got != fresh_pairs(spheres_of(frames[t], radii), box, list_sizes);
      }
    }
    r.seconds_per_step = seconds / double(frames.size());
    r.stats = list.stats();
    return r;
  };
  const auto measurement = [&](double skin, const ListRun& r) {
    return skin_measurement(skin, r.stats, {}, double(n));
  };

  // The model's skin from two reference skins (their own passes).
  const double s0 = reference * r_min, s1 = 2 * reference * r_min;
  const SkinMeasurement m0 = measurement(s0, list_pass(s0, false)), m1 = measurement(s1, list_pass(s1, false));
  const SkinPrediction chosen = choose_skin(m0, m1, dist, 3, kNu, 1e-3 * r_min, 4 * dist.r_max());

  // Timed passes, alternated over rounds, the fastest of each kept.
  const std::vector<double> scan = {0.05, 0.1, 0.2, 0.4, 0.8, 1.6, 3.2};
  std::map<std::string, double> rebuild_best;
  std::map<double, ListRun> list_best;
  double chosen_best = 1e300;
  for (std::uint64_t round = 0; round < rounds; ++round) {
    for (const auto& [name, sizes] : sized) {
      const double s = rebuild_pass(sizes).first;
      if (!rebuild_best.count(name) || s < rebuild_best[name]) rebuild_best[name] = s;
    }
    for (double f : scan) {
      const ListRun r = list_pass(f * r_min, round == 0);
      if (!list_best.count(f) || r.seconds_per_step < list_best[f].seconds_per_step) list_best[f] = r;
    }
    chosen_best = std::min(chosen_best, list_pass(chosen.skin, round == 0).seconds_per_step);
  }
  std::string base_name;
  double base = 1e300;
  for (const auto& [name, s] : rebuild_best)
    if (s < base) base = s, base_name = name;
  std::printf("# N = %zu, nu = %g, omega = %g, %zu Monte Carlo sweeps (%.0f %% of the moves accepted), fastest of "
              "%llu alternated rounds, one thread\n",
              radii.size(), kNu, kOmega, frames.size(), 100 * acceptance, (unsigned long long)rounds);
  std::printf("# grid rebuilt every step: fastest sizes %s, %.3e s/step\n", base_name.c_str(), base);
  for (const SkinMeasurement& m : {m0, m1})
    std::printf("# measured at skin %.3f r_min: %.2f steps/build, travel %.3f r_min/step (x %.3f over two), L/N %.3f, per build grid "
                "%.3e + store %.3e s, per step test %.3e + check %.3e s\n",
                m.skin / r_min, m.steps_per_build, m.travel_per_step / r_min, m.travel_growth, m.candidates_per_n, m.seconds_grid,
                m.seconds_store, m.seconds_test, m.seconds_check);
  std::printf("# model: the skin model's prediction from the two reference skins' measurements\n");
  std::printf("%10s %12s %12s %12s %12s %12s %12s %12s\n", "skin/r_min", "s/step", "model", "speed-up", "steps/build",
              "model", "cand/N", "model");
  double best = 1e300, best_skin = 0;
  for (double f : scan) {
    const ListRun& r = list_best[f];
    const auto& l = r.stats;
    const SkinPrediction pr = predict_skin(m0, m1, dist, 3, kNu, f * r_min);
    std::printf("%10.3f %12.3e %12.3e %12.2f %12.1f %12.1f %12.3f %12.3f\n", f, r.seconds_per_step, pr.seconds_per_step,
                base / r.seconds_per_step, double(l.steps) / double(std::max<std::uint64_t>(1, l.builds)),
                pr.steps_per_build, double(l.candidates_tested) / double(l.steps) / double(n), pr.candidates_per_n);
    if (r.seconds_per_step < best) best = r.seconds_per_step, best_skin = f;
  }
  std::printf("model's skin %.4f r_min (from %.3f and %.3f): %.3e s/step, %.3f of the fastest scanned (%.3f r_min), "
              "speed-up %.2f over the rebuilt grid\n",
              chosen.skin / r_min, reference, 2 * reference, chosen_best, chosen_best / best, best_skin, base / chosen_best);
  std::printf("pairs against a fresh grid every %d steps: %llu mismatches\n", kCheckEvery,
              (unsigned long long)mismatches);
  return mismatches == 0 ? 0 : 1;
}
