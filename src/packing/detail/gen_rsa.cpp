#include "packing/detail/gen_rsa.hpp"

#include <cmath>
#include <cstdio>

#include "packing/detail/gen_insert_grid.hpp"

namespace hgrid::detail {
namespace {

template <int D, Boundary B>
std::size_t rsa(const std::array<double, 3>& box3, const std::vector<double>& radii,
                const std::vector<std::uint32_t>& order, double scale, GenRng& rng, std::vector<double>& pos,
                Progress& progress) {
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
  for (std::size_t m = 0; m < order.size(); ++m) {
    const std::uint32_t i = order[m];
    const double r = scaled[i];
    const int level = grid.level_of(r);
    std::array<double, D> x;
    bool placed = false;
    for (std::uint64_t a = 0; a < kRsaMaxAttempts && !placed; ++a) {
      for (int k = 0; k < D; ++k) {
        const double lo = B == Boundary::walls ? r : 0.0;
        x[k] = lo + rng.uniform() * (box[k] - 2 * lo);
      }
      ++attempts;
      placed = !grid.overlaps(x, r, level);
    }
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
                      const std::vector<std::uint32_t>& order, double scale, GenRng& rng, std::vector<double>& pos,
                      Progress& progress) {
  if (d == 2)
    return b == Boundary::walls ? rsa<2, Boundary::walls>(box, radii, order, scale, rng, pos, progress)
                                : rsa<2, Boundary::periodic>(box, radii, order, scale, rng, pos, progress);
  return b == Boundary::walls ? rsa<3, Boundary::walls>(box, radii, order, scale, rng, pos, progress)
                              : rsa<3, Boundary::periodic>(box, radii, order, scale, rng, pos, progress);
}

}  // namespace hgrid::detail
