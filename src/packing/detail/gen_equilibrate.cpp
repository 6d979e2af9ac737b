#include "packing/detail/gen_equilibrate.hpp"

#include <algorithm>
#include <cstdio>

#include "packing/detail/gen_insert_grid.hpp"

namespace hgrid::detail {
namespace {

template <int D, Boundary B>
bool inside(const std::array<double, D>& x, double r, const Extent<D>& box) {
  if constexpr (B == Boundary::walls)
    for (int k = 0; k < D; ++k)
      if (x[k] < r || x[k] > box[k] - r) return false;
  return true;
}

/// Particles i and j exchange positions if neither then overlaps anything
/// (the two cannot overlap each other: their distance and radius sum stay).
template <int D, Boundary B>
bool try_swap(InsertGrid<D, B>& grid, const std::vector<double>& radii, const Extent<D>& box, std::uint32_t i,
              std::uint32_t j) {
  const std::array<double, D> xi = grid.position(i), xj = grid.position(j);
  if (!inside<D, B>(xj, radii[i], box) || !inside<D, B>(xi, radii[j], box)) return false;
  grid.erase(i);
  grid.erase(j);
  const bool ok = !grid.overlaps(xj, radii[i], 0) && !grid.overlaps(xi, radii[j], 0);
  grid.insert(i, ok ? xj : xi, radii[i]);
  grid.insert(j, ok ? xi : xj, radii[j]);
  return ok;
}

template <int D, Boundary B>
Equilibration run(const std::array<double, 3>& box3, const std::vector<double>& radii, std::vector<double>& pos,
                  int sweeps, GenRng& rng, Progress& progress) {
  Extent<D> box;
  for (int k = 0; k < D; ++k) box[k] = box3[k];
  const std::size_t n = radii.size();
  InsertGrid<D, B> grid(box, radii);
  for (std::size_t i = 0; i < n; ++i) {
    std::array<double, D> x;
    for (int k = 0; k < D; ++k) x[k] = pos[i * D + k];
    grid.insert(static_cast<std::uint32_t>(i), x, radii[i]);
  }
  std::uint64_t accepted = 0, proposed = 0, swapped = 0, swaps = 0;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    for (std::size_t m = 0; m < n; ++m) {
      const auto i = static_cast<std::uint32_t>(rng.bits() % n);
      if (rng.uniform() < kSwapFraction) {
        const auto j = static_cast<std::uint32_t>(rng.bits() % n);
        ++swaps;
        if (j != i && try_swap<D, B>(grid, radii, box, i, j)) ++swapped;
        continue;
      }
      const double r = radii[i];
      std::array<double, D> x = grid.position(i);
      for (int k = 0; k < D; ++k) {
        x[k] += (2 * rng.uniform() - 1) * kMcStep * r;
        if constexpr (B == Boundary::periodic) x[k] = wrap(x[k], box[k]);
      }
      ++proposed;
      if (!inside<D, B>(x, r, box) || grid.overlaps(x, r, 0, i)) continue;
      grid.erase(i);
      grid.insert(i, x, r);
      ++accepted;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "sweep %d, acceptance %.2f (moves), %.2f (swaps)", sweep + 1,
                  static_cast<double>(accepted) / static_cast<double>(std::max<std::uint64_t>(proposed, 1)),
                  static_cast<double>(swapped) / static_cast<double>(std::max<std::uint64_t>(swaps, 1)));
    progress.update(static_cast<double>(sweep + 1) / sweeps, buf);
  }
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < D; ++k) pos[i * D + k] = grid.position(static_cast<std::uint32_t>(i))[k];
  Equilibration e;
  if (proposed) e.displacement_acceptance = static_cast<double>(accepted) / static_cast<double>(proposed);
  if (swaps) e.swap_acceptance = static_cast<double>(swapped) / static_cast<double>(swaps);
  return e;
}

}  // namespace

Equilibration equilibrate(int d, Boundary b, const std::array<double, 3>& box, const std::vector<double>& radii,
                          std::vector<double>& pos, int sweeps, GenRng& rng, Progress& progress) {
  if (d == 2)
    return b == Boundary::walls ? run<2, Boundary::walls>(box, radii, pos, sweeps, rng, progress)
                                : run<2, Boundary::periodic>(box, radii, pos, sweeps, rng, progress);
  return b == Boundary::walls ? run<3, Boundary::walls>(box, radii, pos, sweeps, rng, progress)
                              : run<3, Boundary::periodic>(box, radii, pos, sweeps, rng, progress);
}

}  // namespace hgrid::detail
