// Seeded test packings and pair-set helpers shared by the tests.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "hgridlab/grid/brute_force.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/packing/packing.hpp"

namespace hgrid::test {

using Pair = std::pair<std::uint32_t, std::uint32_t>;

/// A generated packing's achieved packing fraction against the one asked, relative.
inline constexpr double kNuTol = 1e-12;

/// Radius from a truncated power law r^alpha on [1, omega] by inverse CDF.
inline double power_law_radius(double u, double alpha, double omega) {
  if (omega == 1.0) return 1.0;
  const double e = alpha + 1.0;
  if (std::abs(e) < 1e-12) return std::pow(omega, u);
  return std::pow(1.0 + u * (std::pow(omega, e) - 1.0), 1.0 / e);
}

template <int D>
struct Scene {
  std::vector<Sphere<D>> spheres;
  Extent<D> box;
};

/// N random centres (walls: each at least its radius from every wall, when the
/// box allows), radii from the power law, box sized for packing fraction nu.
template <int D>
Scene<D> random_scene(std::size_t n, double nu, double alpha, double omega, Boundary b, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Scene<D> s;
  double vol = 0;
  const double vd = unit_ball_volume(D);
  s.spheres.resize(n);
  for (auto& p : s.spheres) {
    p.r = power_law_radius(u(rng), alpha, omega);
    vol += vd * std::pow(p.r, D);
  }
  const double side = n ? std::pow(vol / nu, 1.0 / D) : 10.0;
  for (int a = 0; a < D; ++a) s.box[a] = side * (1.0 + 0.1 * a);  // not cubic on purpose
  for (auto& p : s.spheres)
    for (int a = 0; a < D; ++a) {
      const double lo = b == Boundary::walls ? std::min(p.r, 0.5 * s.box[a]) : 0.0;
      p.x[a] = lo + u(rng) * (s.box[a] - 2 * lo);
    }
  return s;
}

/// Sizes s_h = 2 r_min omega^(h/L) (exponential), the last set to 2 r_max.
inline std::vector<double> exponential_sizes(int L, double r_min, double r_max) {
  std::vector<double> s;
  for (int h = 1; h <= L; ++h) s.push_back(2 * r_min * std::pow(r_max / r_min, double(h) / L));
  s.back() = 2 * r_max;
  if (L > 1 && r_max == r_min)  // monodisperse: still strictly increasing
    for (int h = 0; h < L; ++h) s[h] = 2 * r_max * (1.0 + h);
  return s;
}

template <int D, Boundary B>
std::vector<Pair> brute_pairs(const Scene<D>& s) {
  std::vector<Pair> out;
  brute_force_pairs<D, B>(std::span<const Sphere<D>>(s.spheres), s.box, [&](std::uint32_t i, std::uint32_t j) {
    out.emplace_back(i, j);
  });
  std::sort(out.begin(), out.end());
  return out;
}

/// The pairs of a grid, sorted (NOT deduplicated: duplicates must show), and
/// its counters; the query on one thread, whatever the grid's params say.
template <Search S, class Count = Uncounted, int D, Boundary B>
std::pair<std::vector<Pair>, Counters> query_pairs(const HGrid<D, B>& grid) {
  std::vector<Pair> out;
  const Counters c =
      grid.template query<S, Count>([&](std::uint32_t i, std::uint32_t j) { out.emplace_back(i, j); }, 1);
  std::sort(out.begin(), out.end());
  return {out, c};
}

/// The same for a new grid of the scene.
template <int D, Boundary B, Search S, class Count = Uncounted>
std::pair<std::vector<Pair>, Counters> grid_pairs(const Scene<D>& s, const std::vector<double>& sizes) {
  const HGrid<D, B> grid(std::span<const Sphere<D>>(s.spheres), s.box, GridParams{sizes, S});
  return query_pairs<S, Count>(grid);
}

/// Every count of two queries equal (gtest checks).
inline void expect_same_counters(const Counters& a, const Counters& b) {
  EXPECT_EQ(a.cell_accesses, b.cell_accesses);
  EXPECT_EQ(a.narrow_phase_checks, b.narrow_phase_checks);
  EXPECT_EQ(a.contacts, b.contacts);
  EXPECT_EQ(a.levels, b.levels);
  EXPECT_EQ(a.particles_per_level, b.particles_per_level);
  EXPECT_EQ(a.accesses_by_level, b.accesses_by_level);
  EXPECT_EQ(a.checks_by_level, b.checks_by_level);
  EXPECT_EQ(a.occupied_cells, b.occupied_cells);
  EXPECT_EQ(a.searches, b.searches);
  EXPECT_EQ(a.rows, b.rows);
  EXPECT_EQ(a.scanned, b.scanned);
  EXPECT_EQ(a.probes, b.probes);
  EXPECT_EQ(a.list_checks, b.list_checks);
  EXPECT_EQ(a.runs, b.runs);
  EXPECT_EQ(a.occupied_by_level, b.occupied_by_level);
  EXPECT_EQ(a.searches_by_level, b.searches_by_level);
  EXPECT_EQ(a.rows_by_level, b.rows_by_level);
}

/// A scene as a Packing with boundary b.
template <int D>
Packing packing_from(const Scene<D>& s, Boundary b) {
  Packing p;
  p.d = D;
  p.boundary = b;
  for (int a = 0; a < D; ++a) p.box[a] = s.box[a];
  for (const auto& q : s.spheres) {
    for (int a = 0; a < D; ++a) p.positions.push_back(q.x[a]);
    p.radii.push_back(q.r);
  }
  return p;
}

/// Calls of operator new since the test program started (test_hgrid_rebuild.cpp
/// counts them), and whether they are counted (not under AddressSanitizer).
std::size_t allocations();
bool counts_allocations();

}  // namespace hgrid::test
