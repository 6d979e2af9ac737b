// The HGrid of a tilted (triclinic) periodic box, and so of a Lees-Edwards
// box (grid/tilted_box.hpp).
//
// The search maps each centre to m = diag(l) s = A x (A = diag(l) H^-1, unit
// upper triangular): the tilted box becomes the orthogonal periodic box of
// sides l, and the lattice's images become that box's images, so the
// orthogonal HGrid searches it. A sphere of radius r becomes an ellipsoid,
// inside a sphere of radius c r, c = the largest singular value of A (1 at
// zero tilt); the grid searches those spheres with its cell sizes times c
// (so every particle keeps its level of insertion), and each pair it finds
// is tested again with the lattice's nearest image. Rounding the fractional
// coordinates finds that image for every overlapping pair when 2 r_max is
// below half the box's narrowest perpendicular width: a vector shorter than
// half of width k has fractional coordinate k in (-1/2, 1/2). A narrower box
// (LAMMPS's own boxes, sheared by fix deform, get there; so does a contact
// list's skin) has the shifts around the rounding tried as well, as many as
// 2 r_max can reach (TiltedBox::image_reach): the box's width is not
// limited. The grid's per-axis minimum image in the mapped box is the
// image nearest there, never farther than the lattice's nearest image
// mapped, so the grid finds every pair at any width. docs/MODEL.md
// section 12 states what it does to the work.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/base/threads.hpp"
#include "hgridlab/grid/counters.hpp"
#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/grid/params.hpp"
#include "hgridlab/grid/tilted_box.hpp"

namespace hgrid {

/// The HGrid of a tilted periodic box: the orthogonal grid of the mapped
/// spheres (see the top of the file), its pairs tested again in the box.
/// The same interface as HGrid for what a measurement needs. Sizes are in
/// the box's units, as for HGrid; at zero tilt it is that grid, counts and all.
template <int D>
class TiltedHGrid {
 public:
  TiltedHGrid(std::span<const Sphere<D>> spheres, const TiltedBox<D>& box, const GridParams& params)
      : box_(box), c_(box.inflation()), x_(spheres.size()), r_(spheres.size()),
        grid_(mapped(spheres, box, params, x_, r_, c_), box.length, scaled(params, c_)) {
    double r_max = 0;
    for (const double r : r_) r_max = std::max(r_max, r);
    reach_ = box_.image_reach(2 * r_max);
  }

  /// f(i, j) or f(t, i, j) (base/threads.hpp) for every pair i < j closer
  /// than r_i + r_j under the lattice's minimum image, once each. Counters:
  /// the mapped grid's accesses and checks (its candidates' second test is
  /// not counted), contacts the pairs handed to f.
  template <Search S, class Count = Uncounted, class F>
  Counters query(F&& f, int threads) const {
    const int T = resolve_threads(threads);
    struct alignas(64) Slot {
      std::uint64_t n = 0;
    };
    std::vector<Slot> found(static_cast<std::size_t>(T));
    Counters c = grid_.template query<S, Count>(
        [&](int t, std::uint32_t i, std::uint32_t j) {
          if (c_ != 1.0) {
            std::array<double, D> n;
            const double s = r_[i] + r_[j];
            if (!(detail::nearest_image<D>(box_, x_[i], x_[j], reach_, n) < s * s)) return;
          }
          ++found[static_cast<std::size_t>(t)].n;
          if constexpr (kTakesThreadIndex<F>) f(t, i, j);
          else f(i, j);
        },
        threads);
    c.contacts = 0;
    for (const auto& s : found) c.contacts += s.n;
    return c;
  }
  template <class Count = Uncounted, class F>
  Counters for_each_pair(F&& f) const {
    return grid_.params().search == Search::top_down ? query<Search::top_down, Count>(f, grid_.params().threads)
                                                     : query<Search::bottom_up, Count>(f, grid_.params().threads);
  }

  const TiltedBox<D>& box() const { return box_; }
  /// c, the factor of the mapped spheres' radii and the grid's cell sizes.
  double inflation() const { return c_; }
  /// The orthogonal grid of the mapped spheres (sizes c times the given ones).
  const HGrid<D, Boundary::periodic>& mapped_grid() const { return grid_; }
  /// The cell sizes in the box's units.
  std::vector<double> sizes() const {
    std::vector<double> s = grid_.sizes();
    if (c_ != 1.0)
      for (auto& v : s) v /= c_;
    return s;
  }
  int levels() const { return grid_.levels(); }
  std::size_t size() const { return grid_.size(); }

 private:
  static std::vector<Sphere<D>> mapped(std::span<const Sphere<D>> in, const TiltedBox<D>& box, const GridParams&,
                                       std::vector<std::array<double, D>>& x, std::vector<double>& r, double c) {
    box.check();
    std::vector<Sphere<D>> out(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
      x[i] = in[i].x;
      r[i] = in[i].r;
      for (int k = 0; k < D; ++k)
        if (!std::isfinite(in[i].x[k]))
          throw InputError("positions", "particle " + std::to_string(i) + ": coordinate not finite");
      out[i].x = c == 1.0 ? in[i].x : box.mapped(in[i].x);
      out[i].r = c * in[i].r;
    }
    return out;
  }
  static GridParams scaled(GridParams p, double c) {
    if (c != 1.0)
      for (auto& s : p.sizes) s *= c;
    return p;
  }

  TiltedBox<D> box_;
  double c_;
  std::vector<std::array<double, D>> x_;
  std::vector<double> r_;
  HGrid<D, Boundary::periodic> grid_;
  std::array<int, D> reach_{};  // shifts tried around the rounding (TiltedBox::image_reach of 2 r_max)
};

/// The O(N^2) reference for a tilted box: f(i, j), i < j, for every pair
/// closer than r_i + r_j in some image, trying the lattice shifts around the
/// fractional rounding of the displacement (so it does not rest on the
/// rounding alone): 1 either side on every axis, or 1 + ceil((r_i + r_j) /
/// the narrowest width) where the pair reaches past half of it (more than
/// TiltedBox::image_reach asks, and counted by other means). Returns the
/// pairs tested. H is upper triangular, so a shift's last Cartesian
/// component depends on its last lattice coordinate only, the one before on
/// the last two: a shift whose component alone reaches r_i + r_j is skipped
/// with those after it (its distance can only be larger), and the rest get
/// the full test.
template <int D, class F>
std::uint64_t brute_force_pairs_tilted(std::span<const Sphere<D>> s, const TiltedBox<D>& box, F&& f) {
  const std::size_t n = s.size();
  const double w = box.min_width();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const auto base = detail::nearest_shift<D>(box, s[i].x, s[j].x);
      const double sum = s[i].r + s[j].r, sum2 = sum * sum;
      const int M = sum < 0.5 * w ? 1 : 1 + static_cast<int>(std::ceil(sum / w));
      std::array<double, D> shift = base;
      bool hit = false;
      for (int mz = -M; mz <= M && !hit; ++mz) {
        shift[D - 1] = base[D - 1] + mz;
        // The components as TiltedBox::cartesian and tilted_dist2 form them
        // (the same expressions, so a skip never drops a pair the full test keeps).
        const double ez = s[j].x[D - 1] - s[i].x[D - 1] + box.length[D - 1] * shift[D - 1];
        if (ez * ez >= sum2) continue;
        const int kMid = D == 3 ? M : 0;  // in 2D no middle axis: one pass
        for (int my = -kMid; my <= kMid && !hit; ++my) {
          if constexpr (D == 3) {
            shift[1] = base[1] + my;
            const double ey = s[j].x[1] - s[i].x[1] + (box.length[1] * shift[1] + box.tilt[2] * shift[2]);
            if (ey * ey >= sum2) continue;
          }
          for (int mx = -M; mx <= M; ++mx) {
            shift[0] = base[0] + mx;
            if (detail::tilted_dist2<D>(box, s[i].x, s[j].x, shift) < sum2) {
              f(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
              hit = true;
              break;
            }
          }
        }
      }
    }
  return n * (n - (n > 0)) / 2;
}

}  // namespace hgrid
