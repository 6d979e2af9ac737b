// The time model's terms: counted (from a counted query) and expected (from
// the cost model's integrals); the time-optimal cell sizes. docs/MODEL.md section 9.
#include "hgridlab/model/time_model.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/model/detail/coordinate_search.hpp"

namespace hgrid {

namespace {

// The grid's choice of directory (grid/detail/levels.hpp): a rank bitmap
// while a level has at most this many cells per particle plus a constant.
constexpr double kRankCellsPerParticle = 64;
constexpr double kRankMinCells = 65536;
constexpr double kBitsPerWord = 64;
// A range of more than this many particles is tested as a run, a shorter
// one gathered into the candidate list (HGrid::kShortRange).
constexpr int kShortRange = 4;

/// P(Poisson(mu) >= k).
double at_least(double mu, int k) {
  if (!(mu > 0)) return k <= 0 ? 1.0 : 0.0;
  double term = std::exp(-mu), below = 0;
  for (int i = 0; i < k; ++i) {
    below += term;
    term *= mu / (i + 1);
  }
  return std::max(0.0, 1.0 - below);
}

/// Expected checks in long ranges, E[X 1(X > kShortRange)], for a range
/// holding X ~ Poisson(mu) particles: mu P(Poisson(mu) >= kShortRange).
double run_part(double mu) { return mu * at_least(mu, kShortRange); }

/// Probability that such a range is long (tested as a run).
double run_prob(double mu) { return at_least(mu, kShortRange + 1); }

// The coordinate search of time_optimal_sizes.
constexpr int kExtraLevels = 3;             // L from 1 to L* + this
constexpr double kSteps[] = {1.25, 1.1, 1.03};

}  // namespace

std::array<double, kQueryTerms> query_terms(const TimeTerms& t) {
  return {t.particles, t.occupied_cells, t.run_checks, t.list_checks, t.runs,
          t.searches,  t.rows,           t.scanned,    t.probes,      t.contacts};
}

std::array<double, kBuildTerms> build_terms(const TimeTerms& t) {
  return {t.particles, t.level_steps, t.sort_passes, t.bucket_passes, t.directory_words, t.directory_slots};
}

PredictedSeconds predict_seconds(const TimeCoefficients& c, const TimeTerms& t) {
  PredictedSeconds out;
  const auto q = query_terms(t);
  const auto b = build_terms(t);
  for (int k = 0; k < kQueryTerms; ++k) out.query += c.query[k] * q[k];
  for (int k = 0; k < kBuildTerms; ++k) out.build += c.build[k] * b[k];
  return out;
}

TimeTerms counted_time_terms(const Counters& c, const BuildWork& b) {
  TimeTerms t;
  t.particles = static_cast<double>(c.particles());
  t.occupied_cells = static_cast<double>(c.occupied_cells);
  t.list_checks = static_cast<double>(c.list_checks);
  t.run_checks = static_cast<double>(c.narrow_phase_checks) - t.list_checks;
  t.runs = static_cast<double>(c.runs);
  t.searches = static_cast<double>(c.searches);
  t.rows = static_cast<double>(c.rows);
  t.scanned = static_cast<double>(c.scanned);
  t.probes = static_cast<double>(c.probes);
  t.contacts = static_cast<double>(c.contacts);
  t.directory_words = static_cast<double>(b.directory_words);
  t.directory_slots = static_cast<double>(b.directory_slots);
  t.sort_passes = b.sort.particle_passes;
  t.bucket_passes = b.sort.bucket_passes;
  for (int h = 0; h < c.levels; ++h) t.level_steps += double(h) * double(c.particles_per_level[h]);
  return t;
}

TimeTerms expected_time_terms(const Distribution& dist, const ModelParams& p, const std::vector<double>& s,
                              double n, double box_volume) {
  const ModelResult m = evaluate_model(dist, p, s);  // validates p and the sizes
  const int L = m.levels(), d = p.d;
  const bool td = p.search == Search::top_down;
  const double vp = unit_ball_volume(d) * dist.moment(d, 0.0, dist.r_max());
  TimeTerms t;
  t.particles = n;
  double checks = n * m.T_cd_over_N;
  const double half_stencil = d == 2 ? 4 : 13;  // (3^d - 1) / 2 neighbour cells
  std::vector<char> ranked(L);
  std::vector<double> cells_of(L);  // filled volume / s_h^d
  for (int h = 0; h < L; ++h) cells_of[h] = n * vp / (p.nu * std::pow(s[h], d));
  const double box_over_filled = box_volume > 0 ? std::max(1.0, box_volume * p.nu / (n * vp)) : 1.0;
  for (int h = 0; h < L; ++h) {
    const double nh = n * m.P[h];
    const double cells = cells_of[h], laid_out = cells * box_over_filled;  // the build's cells: the whole box's
    ranked[h] = laid_out <= kRankCellsPerParticle * nh + kRankMinCells;
    const double occupied = nh > 0 ? cells * -std::expm1(-nh / cells) : 0.0;  // Poisson occupancy
    t.occupied_cells += occupied;
    t.level_steps += h * nh;
    const LevelSortWork sw = level_sort_work(static_cast<std::uint64_t>(std::max(1.0, laid_out)),
                                             static_cast<std::uint64_t>(n), L);
    t.sort_passes += sw.passes * nh;
    t.bucket_passes += sw.passes * double(sw.buckets);
    const double mh = nh / cells;
    // Same level, per particle: the rest of its own cell (a run, m/2 on
    // average); on a ranked level the half stencil's rows of 3 cells
    // ((3^(d-1) - 1) / 2 of them) and the next cell of its own row, on a
    // hashed one the half stencil's cells one by one.
    // The own cell's rest is a run when it is not empty: per particle
    // 1 - (1 - e^-m) / m on average over a Poisson cell.
    double run_checks = 0.5 * mh, runs = mh > 0 ? 1 + std::expm1(-mh) / mh : 0;
    if (ranked[h]) {
      t.directory_words += std::floor(laid_out / kBitsPerWord) + 1;
      run_checks += (half_stencil - 1) / 3 * run_part(3 * mh) + run_part(mh);
      runs += (half_stencil - 1) / 3 * run_prob(3 * mh) + run_prob(mh);
    } else {
      t.directory_slots += double(std::max<std::uint64_t>(16, std::bit_ceil(static_cast<std::uint64_t>(2 * nh))));
      t.probes += occupied * half_stencil;
      run_checks += half_stencil * run_part(mh);
      runs += half_stencil * run_prob(mh);
    }
    t.run_checks += nh * run_checks;
    t.runs += nh * runs;
  }
  for (int h = 0; h < L; ++h) {
    const double nh = n * m.P[h];
    if (!(nh > 0)) continue;
    const double lo = h == 0 ? 0.0 : 0.5 * s[h - 1], hi = 0.5 * s[h];
    for (int j = td ? 0 : h + 1; j < (td ? h : L); ++j) {
      t.searches += nh;
      const double nj = n * m.P[j];
      const double box = cross_level_cells(dist, d, s, j + 1, h + 1);
      const double pair_checks = n * m.T_cd_pair[h * L + j];
      if (box > nj) {  // the scan tests each particle in the box as it finds it: runs
        t.scanned += nh * nj;
        t.run_checks += pair_checks;
        continue;
      }
      if (!ranked[j]) {  // a hashed level's cells are tested as ranges, one by one: runs
        t.probes += nh * box;
        t.run_checks += pair_checks;
        t.runs += nh * box * at_least(nj / cells_of[j], 1);
        continue;
      }
      // n int over level h of (2 + 2r/s_j)^(d-1) f(r) dr, expanded in moments.
      double rows = 0, binom = 1;
      for (int i = 0; i < d; ++i) {
        rows += std::pow(2.0, d - 1) * binom * std::pow(s[j], -i) * dist.moment(i, lo, hi);
        binom = binom * (d - 1 - i) / (i + 1);
      }
      t.rows += n * rows;
      // A row of the box holds box / rows cells, each m_j particles on average.
      const double per_row = rows > 0 ? box * m.P[h] / rows * (nj / cells_of[j]) : 0;
      if (per_row > 0) {
        t.run_checks += pair_checks * run_part(per_row) / per_row;
        t.runs += n * rows * run_prob(per_row);
      }
    }
  }
  t.list_checks = checks - t.run_checks;
  // Pairs closer than r_i + r_j among independent centres: n^2 / (2 V) times
  // v_d E[(r_i + r_j)^d], with V = n V_p / nu and the binomial expansion.
  double overlap = 0, binom = 1;
  for (int k = 0; k <= d; ++k) {
    overlap += binom * dist.moment(k, 0.0, dist.r_max()) * dist.moment(d - k, 0.0, dist.r_max());
    binom = binom * (d - k) / (k + 1);
  }
  t.contacts = 0.5 * n * p.nu / vp * unit_ball_volume(d) * overlap;
  return t;
}

TimeOptimalSizes time_optimal_sizes(const Distribution& dist, const ModelParams& p, const TimeCoefficients& c,
                                    double n, double box_volume) {
  const double top = 2.0 * dist.r_max(), bottom = 2.0 * dist.r_min();
  TimeOptimalSizes best;
  double best_seconds = std::numeric_limits<double>::infinity();
  const auto seconds = [&](const std::vector<double>& s) {
    ++best.evaluations;
    return predict_seconds(c, expected_time_terms(dist, p, sizes_for_grid(s, top), n, box_volume)).total();
  };
  const int L_star = choose_cell_sizes(dist, p, CellMethod::optimal).levels;
  for (int L = 1; L <= L_star + kExtraLevels; ++L) {
    std::vector<double> s = L == 1 ? std::vector<double>{top} : cell_sizes(dist, p, CellMethod::optimal, L);
    double here = seconds(s);
    detail::coordinate_search(s, here, bottom, kSteps, seconds);
    if (here < best_seconds) {
      best_seconds = here;
      best.sizes = sizes_for_grid(s, top);
    }
  }
  best.seconds = predict_seconds(c, expected_time_terms(dist, p, best.sizes, n, box_volume));
  return best;
}

}  // namespace hgrid
