// Domain decomposition of the box into bricks, one per rank: who owns a
// particle, which other ranks need it as a ghost (a level-aware layer), and
// the rule that reports every overlapping pair on exactly one rank. No MPI
// here: the tool's transport (src/mpi) and the tests use the same rules.
//
// The rule (docs/MODEL.md section 10). A pair of particles with one owner
// is reported by that owner. Otherwise order the two by (r, owner rank): the
// pair is reported by the rank that owns its lower particle a. Its partner b has r_b >= r_a, so |x_a - x_b| < r_a + r_b <=
// 2 r_b: b lies within 2 r_b of a's brick. Hence a particle of radius r is
// sent only to the bricks within 2 r of its centre (plus a rounding margin):
// a small particle only as far as a small search reaches, instead of one
// 2 r_max shell for every particle (what LAMMPS's `comm_modify mode multi`
// addresses with cutoffs per type pair).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/grid/geometry.hpp"

namespace hgrid {

/// True if particle a comes before b in the reporting order: (radius, owner
/// rank). Only asked of particles with different owners.
inline bool reports_before(double r_a, int owner_a, double r_b, int owner_b) {
  return r_a < r_b || (r_a == r_b && owner_a < owner_b);
}

/// The distance up to which a particle of radius r is sent as a ghost: 2 r,
/// widened by a margin that covers the rounding of the overlap test and of
/// the brick bounds (relative 1e-9 of r, absolute 1e-12 of the longest side).
inline double ghost_reach(double r, double longest_side) { return 2 * r * (1 + 1e-9) + 1e-12 * longest_side; }

/// The box cut into dims[0] x ... x dims[D-1] equal bricks; brick (b_0, ...,
/// b_{D-1}) is rank (b_0 dims_1 + b_1) dims_2 + b_2 (last axis fastest).
template <int D>
class Bricks {
 public:
  /// `ranks` bricks: the factorisation of ranks into D factors whose bricks
  /// have the least surface (closest to cubes) for this box.
  Bricks(const Extent<D>& box, int ranks, Boundary boundary) : box_(box), boundary_(boundary) {
    if (ranks < 1) throw InputError("ranks", "must be >= 1");
    double best = std::numeric_limits<double>::infinity();
    std::array<int, D> f{};
    auto consider = [&] {
      double area = 0;  // surface of one brick, up to a common factor
      for (int a = 0; a < D; ++a) {
        double face = 1;
        for (int b = 0; b < D; ++b)
          if (b != a) face *= box_[b] / f[b];
        area += face;
      }
      if (area < best * (1 - 1e-12)) best = area, dims_ = f;
    };
    for (int p = 1; p <= ranks; ++p) {
      if (ranks % p) continue;
      f[0] = p;
      if constexpr (D == 2) {
        f[1] = ranks / p;
        consider();
      } else {
        for (int q = 1; q <= ranks / p; ++q) {
          if ((ranks / p) % q) continue;
          f[1] = q;
          f[2] = ranks / p / q;
          consider();
        }
      }
    }
  }

  int ranks() const {
    int n = 1;
    for (int a = 0; a < D; ++a) n *= dims_[a];
    return n;
  }
  const std::array<int, D>& dims() const { return dims_; }
  const Extent<D>& box() const { return box_; }

  /// The brick index along axis a of coordinate x (periodic: wrapped first;
  /// walls: a centre on the far wall belongs to the last brick).
  int index(int a, double x) const {
    if (boundary_ == Boundary::periodic) x = detail::wrap(x, box_[a]);
    const double k = std::floor(x / box_[a] * dims_[a]);
    return static_cast<int>(std::clamp(k, 0.0, static_cast<double>(dims_[a] - 1)));
  }
  /// The rank owning a centre.
  int owner(const std::array<double, D>& x) const {
    int r = 0;
    for (int a = 0; a < D; ++a) r = r * dims_[a] + index(a, x[a]);
    return r;
  }
  double lo(int a, int b) const { return box_[a] * b / dims_[a]; }
  double hi(int a, int b) const { return box_[a] * (b + 1) / dims_[a]; }

  /// Calls f(rank) once for every rank other than `self` whose brick comes
  /// closer than `reach` to x (periodic: its nearest image).
  template <class F>
  void for_each_within(const std::array<double, D>& x, double reach, int self, F&& f) const {
    std::array<double, D> xs;
    int brick = 0;
    if (!inside(x, reach, xs, brick)) near_ranks(xs, reach, self, f);
  }

  /// The rank owning centre x (owner(x)), and f(rank) for every other rank
  /// whose brick comes closer than `reach` to x (for_each_within(x, reach,
  /// owner(x), f)), in one pass over the axes.
  template <class F>
  int place(const std::array<double, D>& x, double reach, F&& f) const {
    std::array<double, D> xs;
    int own = 0;
    if (!inside(x, reach, xs, own)) near_ranks(xs, reach, own, f);
    return own;
  }

  /// Volume of one brick's halo of width w: the brick grown by w (Steiner's
  /// formula for a box) minus the brick, at most the rest of the box.
  double halo_volume(double w) const {
    std::array<double, D> e;
    double box_volume = 1, brick = 1;
    for (int a = 0; a < D; ++a) e[a] = box_[a] / dims_[a], brick *= e[a], box_volume *= box_[a];
    double grown;
    if constexpr (D == 2) {
      grown = brick + 2 * (e[0] + e[1]) * w + M_PI * w * w;
    } else {
      grown = brick + 2 * (e[0] * e[1] + e[1] * e[2] + e[0] * e[2]) * w + M_PI * (e[0] + e[1] + e[2]) * w * w +
              4.0 / 3.0 * M_PI * w * w * w;
    }
    return std::min(grown, box_volume) - brick;
  }

 private:
  /// xs: x wrapped (periodic); brick: the rank owning x. True if x is
  /// farther than `reach` from every face of that brick (most particles):
  /// then no other brick is within reach (periodic images lie beyond the
  /// faces too).
  bool inside(const std::array<double, D>& x, double reach, std::array<double, D>& xs, int& brick) const {
    bool in = true;
    brick = 0;
    for (int a = 0; a < D; ++a) {
      xs[a] = boundary_ == Boundary::periodic ? detail::wrap(x[a], box_[a]) : x[a];
      if (dims_[a] == 1) continue;  // brick index 0, no face to come near
      const int b = index(a, xs[a]);
      brick = brick * dims_[a] + b;
      in = in && xs[a] - reach > lo(a, b) && xs[a] + reach < hi(a, b);
    }
    return in;
  }

  /// f(rank) for every rank but `self` whose brick is within reach of the
  /// wrapped centre xs.
  template <class F>
  void near_ranks(const std::array<double, D>& xs, double reach, int self, F&& f) const {
    // Per axis: the bricks within reach and their distance (buffers kept
    // per thread: no allocation per call; so f must not call this again).
    thread_local std::array<std::vector<std::pair<int, double>>, D> near;
    for (int a = 0; a < D; ++a) {
      near[a].clear();
      const int n = dims_[a];
      const double w = box_[a] / n;
      const double xa = xs[a];
      const auto first = static_cast<std::int64_t>(std::floor((xa - reach) / w)) - 1;
      const auto last = static_cast<std::int64_t>(std::floor((xa + reach) / w)) + 1;
      const bool all = last - first + 1 >= n;
      for (std::int64_t k = all ? 0 : first; k <= (all ? n - 1 : last); ++k) {
        int b = static_cast<int>(k);
        if (boundary_ == Boundary::walls) {
          if (k < 0 || k >= n) continue;
        } else {
          b = static_cast<int>(((k % n) + n) % n);
        }
        double dist = axis_distance(xa, lo(a, b), hi(a, b));
        if (boundary_ == Boundary::periodic)
          dist = std::min({dist, axis_distance(xa - box_[a], lo(a, b), hi(a, b)),
                           axis_distance(xa + box_[a], lo(a, b), hi(a, b))});
        if (dist >= reach) continue;
        auto& list = near[a];
        // A range that wraps can meet a brick twice: keep it once.
        if (std::none_of(list.begin(), list.end(), [&](const auto& e) { return e.first == b; }))
          list.emplace_back(b, dist);
      }
    }
    const double reach2 = reach * reach;
    std::array<std::size_t, D> it{};
    for (;;) {
      double d2 = 0;
      int rank = 0;
      for (int a = 0; a < D; ++a) {
        if (near[a].empty()) return;
        const auto& [b, dist] = near[a][it[a]];
        d2 += dist * dist;
        rank = rank * dims_[a] + b;
      }
      if (d2 < reach2 && rank != self) f(rank);
      int a = D - 1;
      while (a >= 0 && ++it[a] == near[a].size()) it[a--] = 0;
      if (a < 0) return;
    }
  }

  static double axis_distance(double x, double lo, double hi) { return std::max({0.0, lo - x, x - hi}); }
  Extent<D> box_;
  Boundary boundary_;
  std::array<int, D> dims_{};
};

}  // namespace hgrid
