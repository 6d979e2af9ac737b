// CGAL box_intersection_d on the spheres' bounding boxes, then the exact
// sphere test (compiled only when CGAL is found: HGRID_HAVE_CGAL).
//
// CGAL knows no periodic boundaries: the periodic images and the rule that
// counts each pair once are in periodic_images.hpp. Image creation is timed
// with the rest.
#pragma once
#ifdef HGRID_HAVE_CGAL
#include <CGAL/box_intersection_d.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "bench/detail/periodic_images.hpp"
#include "hgridlab/grid/geometry.hpp"

namespace hgrid::bench {

template <int D, Boundary B>
std::uint64_t cgal_pairs(std::span<const Sphere<D>> s, const Extent<D>& box) {
  std::vector<Image<D>> img;
  make_images<D, B>(s, box, img);
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
    if (counts_as_contact<D>(a.handle(), b.handle())) ++pairs;
  });
  return pairs;
}

}  // namespace hgrid::bench
#endif
