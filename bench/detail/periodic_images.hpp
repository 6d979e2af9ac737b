// The spheres as the box-overlap peers (CGAL, Embree, Bullet) see them: none
// of them knows periodic boundaries, so in a periodic box every particle whose
// box, shifted by a combination of -A, 0, +A per axis, still reaches the slab
// [-r_max, A + r_max] (where every original box lies) is added as an image.
// A candidate pair of images (p, q) with original indices i < j counts when
// i's image is the original and the exact test on the actual (shifted)
// centres succeeds; as A > 2 (r_i + r_j), that shift is the minimum image, so
// every pair is counted exactly once (provided the peer reports each
// unordered pair of images once).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "hgridlab/grid/geometry.hpp"

namespace hgrid::bench {

/// x rounded toward -infinity (dir < 0) or +infinity (dir > 0) in the peer's
/// coordinate type T, so that a box in T still holds the box in double
/// (exact when T is double).
template <class T>
T round_outward(double x, int dir) {
  const T f = static_cast<T>(x);
  const T inf = std::numeric_limits<T>::infinity();
  if (dir < 0 && static_cast<double>(f) > x) return std::nextafter(f, -inf);
  if (dir > 0 && static_cast<double>(f) < x) return std::nextafter(f, inf);
  return f;
}

/// One timed build + query of a peer: seconds and the pair count.
struct PeerRun {
  double seconds;
  std::uint64_t pairs;
};

template <int D>
struct Image {
  std::array<double, D> x;
  double r;
  std::uint32_t id;
  bool original;
};

/// The originals, then (periodic boxes) their images near the faces; `img` is
/// cleared first.
template <int D, Boundary B>
void make_images(std::span<const Sphere<D>> s, const Extent<D>& box, std::vector<Image<D>>& img) {
  img.clear();
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
}

/// Whether a candidate pair of images (either order) is one contact, counted
/// once (see the top of this file).
template <int D>
inline bool counts_as_contact(const Image<D>* p, const Image<D>* q) {
  if (p->id > q->id) std::swap(p, q);
  if (!p->original || p->id == q->id) return false;
  double d2 = 0;
  for (int k = 0; k < D; ++k) d2 += (p->x[k] - q->x[k]) * (p->x[k] - q->x[k]);
  const double rs = p->r + q->r;
  return d2 < rs * rs;
}

}  // namespace hgrid::bench
