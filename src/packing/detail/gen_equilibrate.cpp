#include "packing/detail/gen_equilibrate.hpp"

#include <cstdio>

#include "packing/detail/gen_insert_grid.hpp"

namespace hgrid::detail {
namespace {

template <int D, Boundary B>
double run(const std::array<double, 3>& box3, const std::vector<double>& radii, std::vector<double>& pos,
           GenRng& rng, Progress& progress) {
  Extent<D> box;
  for (int k = 0; k < D; ++k) box[k] = box3[k];
  const std::size_t n = radii.size();
  InsertGrid<D, B> grid(box, radii);
  for (std::size_t i = 0; i < n; ++i) {
    std::array<double, D> x;
    for (int k = 0; k < D; ++k) x[k] = pos[i * D + k];
    grid.insert(static_cast<std::uint32_t>(i), x, radii[i]);
  }
  std::uint64_t accepted = 0, proposed = 0;
  for (int sweep = 0; sweep < kEquilibrationSweeps; ++sweep) {
    for (std::size_t m = 0; m < n; ++m) {
      const auto i = static_cast<std::uint32_t>(rng.bits() % n);
      const double r = radii[i];
      std::array<double, D> x = grid.position(i);
      bool inside = true;
      for (int k = 0; k < D; ++k) {
        x[k] += (2 * rng.uniform() - 1) * kMcStep * r;
        if constexpr (B == Boundary::periodic) x[k] = wrap(x[k], box[k]);
        else inside = inside && x[k] >= r && x[k] <= box[k] - r;
      }
      ++proposed;
      if (!inside || grid.overlaps(x, r, 0, i)) continue;
      grid.erase(i);
      grid.insert(i, x, r);
      ++accepted;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "sweep %d, acceptance %.2f", sweep + 1,
                  static_cast<double>(accepted) / static_cast<double>(proposed));
    progress.update(static_cast<double>(sweep + 1) / kEquilibrationSweeps, buf);
  }
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < D; ++k) pos[i * D + k] = grid.position(static_cast<std::uint32_t>(i))[k];
  return proposed ? static_cast<double>(accepted) / static_cast<double>(proposed) : 0.0;
}

}  // namespace

double equilibrate(int d, Boundary b, const std::array<double, 3>& box, const std::vector<double>& radii,
                   std::vector<double>& pos, GenRng& rng, Progress& progress) {
  if (d == 2)
    return b == Boundary::walls ? run<2, Boundary::walls>(box, radii, pos, rng, progress)
                                : run<2, Boundary::periodic>(box, radii, pos, rng, progress);
  return b == Boundary::walls ? run<3, Boundary::walls>(box, radii, pos, rng, progress)
                              : run<3, Boundary::periodic>(box, radii, pos, rng, progress);
}

}  // namespace hgrid::detail
