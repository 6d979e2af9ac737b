#include "hgridlab/packing/detail/gen_rsa.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>

#include "hgridlab/packing/detail/gen_insert_grid.hpp"

namespace hgrid::detail {
namespace {

// Trials per particle (moving average) from which a particle's trials are
// tried several at a time on threads; below it one thread is faster.
constexpr double kBatchFromTrials = 6.0;
constexpr std::size_t kMaxBatch = 4096;
constexpr int kChunk = 4;  // trials per handout in a batch

template <int D, Boundary B>
std::size_t rsa(const std::array<double, 3>& box3, const std::vector<double>& radii,
                const std::vector<std::uint32_t>& order, double scale, int threads, GenRng& rng,
                std::vector<double>& pos, Progress& progress) {
  Extent<D> box;
  for (int k = 0; k < D; ++k) box[k] = box3[k];
  std::vector<double> scaled(radii.size());
  double total = 0;
  for (std::size_t i = 0; i < radii.size(); ++i) {
    scaled[i] = scale * radii[i];
    total += std::pow(scaled[i], D);
  }
  InsertGrid<D, B> grid(box, scaled);
  double done = 0;
  std::uint64_t attempts = 0;
  double mean_trials = 1.0;  // moving average over the last ~64 particles
  std::vector<double> ahead;  // uniforms of the next trials, for a batch
  for (std::size_t m = 0; m < order.size(); ++m) {
    const std::uint32_t i = order[m];
    const double r = scaled[i];
    const int level = grid.level_of(r);
    const double lo = B == Boundary::walls ? r : 0.0;
    auto trial_position = [&](const double* u) {
      std::array<double, D> x;
      for (int k = 0; k < D; ++k) x[k] = lo + u[k] * (box[k] - 2 * lo);
      return x;
    };
    std::array<double, D> x;
    bool placed = false;
    std::uint64_t a = 0;
    while (a < kRsaMaxAttempts && !placed) {
      if (threads <= 1 || mean_trials < kBatchFromTrials) {
        double u[D];
        for (int k = 0; k < D; ++k) u[k] = rng.uniform();
        x = trial_position(u);
        ++a;
        placed = !grid.overlaps(x, r, level);
        continue;
      }
      // Several trials at once, exactly those one thread would make next: their
      // uniforms come from a copy of the generator; the first trial that fits
      // wins, and the generator then advances past it alone, as one thread's
      // would. A trial after a fitting one is skipped once that one is known.
      const std::size_t batch = static_cast<std::size_t>(
          std::min<double>({2.0 * mean_trials + 8.0 * threads, static_cast<double>(kMaxBatch),
                            static_cast<double>(kRsaMaxAttempts - a)}));
      GenRng copy = rng;
      ahead.resize(batch * D);
      for (double& u : ahead) u = copy.uniform();
      std::atomic<std::size_t> first{batch};
      const auto chunks = static_cast<std::ptrdiff_t>((batch + kChunk - 1) / kChunk);
#if defined(_OPENMP)
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
#endif
      for (std::ptrdiff_t c = 0; c < chunks; ++c) {
        const std::size_t t0 = static_cast<std::size_t>(c) * kChunk, t1 = std::min(batch, t0 + kChunk);
        for (std::size_t t = t0; t < t1 && t < first.load(std::memory_order_relaxed); ++t) {
          if (grid.overlaps(trial_position(&ahead[t * D]), r, level)) continue;
          std::size_t f = first.load(std::memory_order_relaxed);
          while (t < f && !first.compare_exchange_weak(f, t, std::memory_order_relaxed)) {
          }
          break;
        }
      }
      const std::size_t used = std::min(batch, first.load() + 1);
      for (std::size_t k = 0; k < used * D; ++k) rng.uniform();
      a += used;
      if (first.load() < batch) {
        x = trial_position(&ahead[first.load() * D]);
        placed = true;
      }
    }
    attempts += a;
    mean_trials += (static_cast<double>(a) - mean_trials) / 64.0;
    if (!placed) return m;
    grid.insert(static_cast<std::uint32_t>(m), x, r);
    for (int k = 0; k < D; ++k) pos[static_cast<std::size_t>(i) * D + k] = x[k];
    done += std::pow(r, D);
    if ((m & 1023) == 0) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "placed %zu, %.3g trials each", m + 1,
                    static_cast<double>(attempts) / static_cast<double>(m + 1));
      progress.update(done / total, buf);
    }
  }
  return order.size();
}

}  // namespace

std::size_t rsa_place(int d, Boundary b, const std::array<double, 3>& box, const std::vector<double>& radii,
                      const std::vector<std::uint32_t>& order, double scale, int threads, GenRng& rng,
                      std::vector<double>& pos, Progress& progress) {
  if (d == 2)
    return b == Boundary::walls ? rsa<2, Boundary::walls>(box, radii, order, scale, threads, rng, pos, progress)
                                : rsa<2, Boundary::periodic>(box, radii, order, scale, threads, rng, pos, progress);
  return b == Boundary::walls ? rsa<3, Boundary::walls>(box, radii, order, scale, threads, rng, pos, progress)
                              : rsa<3, Boundary::periodic>(box, radii, order, scale, threads, rng, pos, progress);
}

}  // namespace hgrid::detail
