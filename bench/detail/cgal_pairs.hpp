// CGAL box_intersection_d on the spheres' bounding boxes, then the exact
// sphere test (compiled only when CGAL is found: HGRID_HAVE_CGAL).
//
// CGAL knows no periodic boundaries. In a periodic box every particle whose
// box, shifted by a combination of -A, 0, +A per axis, still reaches the slab
// [-r_max, A + r_max] (where every original box lies) is added as an image.
// A reported box pair (a, b) with original indices i < j is kept only when
// i's box is the original (not an image) and the exact test on the actual
// (shifted) centres succeeds; as A > 2 (r_i + r_j), that shift is the minimum
// image, so every pair is found exactly once. Image creation is timed with the rest.
#pragma once
#ifdef HGRID_HAVE_CGAL
#include <CGAL/box_intersection_d.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "grid/geometry.hpp"

namespace hgrid::bench {

template <int D>
struct Image {
  std::array<double, D> x;
  double r;
  std::uint32_t id;
  bool original;
};

template <int D, Boundary B>
std::uint64_t cgal_pairs(std::span<const Sphere<D>> s, const Extent<D>& box) {
  std::vector<Image<D>> img;
  img.reserve(s.size() + s.size() / 4);
  double rmax = 0;
  for (const auto& p : s) rmax = std::max(rmax, p.r);
  for (std::uint32_t i = 0; i < s.size(); ++i) {
    img.push_back({s[i].x, s[i].r, i, true});
    if constexpr (B == Boundary::periodic) {
      int nshift = 1;
      for (int a = 0; a < D; ++a) nshift *= 3;
      for (int code = 0; code < nshift; ++code) {
        int c = code;
        bool zero = true, keep = true;
        std::array<double, D> x = s[i].x;
        for (int a = 0; a < D; ++a, c /= 3) {
          const int k = c % 3 - 1;
          if (k != 0) zero = false;
          x[a] += k * box[a];
          if (x[a] + s[i].r < -rmax || x[a] - s[i].r > box[a] + rmax) keep = false;
        }
        if (!zero && keep) img.push_back({x, s[i].r, i, false});
      }
    }
  }
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, D, const Image<D>*>;
  std::vector<Box> boxes;
  boxes.reserve(img.size());
  for (const auto& m : img) {
    double lo[D], hi[D];
    for (int a = 0; a < D; ++a) lo[a] = m.x[a] - m.r, hi[a] = m.x[a] + m.r;
    boxes.emplace_back(lo, hi, &m);
  }
  std::uint64_t pairs = 0;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&pairs](const Box& a, const Box& b) {
    const Image<D>* p = a.handle();
    const Image<D>* q = b.handle();
    if (p->id > q->id) std::swap(p, q);
    if (!p->original || p->id == q->id) return;
    double d2 = 0;
    for (int k = 0; k < D; ++k) d2 += (p->x[k] - q->x[k]) * (p->x[k] - q->x[k]);
    const double rs = p->r + q->r;
    if (d2 < rs * rs) ++pairs;
  });
  return pairs;
}

}  // namespace hgrid::bench
#endif
