#include "hgridlab/model/lammps_multi.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hgridlab/base/error.hpp"
#include "hgridlab/model/detail/coordinate_search.hpp"

namespace hgrid {
namespace {

/// LAMMPS's bins of collection j along one axis: as many of side >= c_j / 2
/// as fit the box, so the side is a little above c_j / 2.
struct Axis {
  double count = 1, side = 0;
};

Axis bins_along(double box_side, double bound) {
  Axis a;
  a.count = std::max(1.0, std::floor(box_side / (0.5 * bound)));
  a.side = box_side / a.count;
  return a;
}

/// Stencil bins of a bin grid with sides `bin` for the pair cutoff `cut`:
/// offsets whose bin's nearest point to the central bin is within cut
/// (LAMMPS's bin_distance rule). The full stencil, self included.
double full_stencil(std::span<const Axis> bin, double cut) {
  const int d = static_cast<int>(bin.size());
  int reach[3] = {0, 0, 0};
  for (int a = 0; a < d; ++a) {
    reach[a] = static_cast<int>(cut / bin[a].side);
    if (reach[a] * bin[a].side < cut) ++reach[a];
  }
  auto gap2 = [&](int a, int o) {
    const double g = o == 0 ? 0.0 : (std::abs(o) - 1) * bin[a].side;
    return g * g;
  };
  const double cut2 = cut * cut;
  double n = 0;
  for (int x = -reach[0]; x <= reach[0]; ++x)
    for (int y = -reach[1]; y <= reach[1]; ++y) {
      const double xy = gap2(0, x) + gap2(1, y);
      if (d == 2) {
        n += xy <= cut2;
        continue;
      }
      for (int z = -reach[2]; z <= reach[2]; ++z) n += xy + gap2(2, z) <= cut2;
    }
  return n;
}

}  // namespace

LammpsCoefficients default_lammps_coefficients() {
  // `build/lammps_model` (results/lammps-model/fit.json, train.csv): Intel
  // Xeon VM, Debian LAMMPS 7 Jan 2022, one rank, 2026-11-26; 115 builds on 5
  // training packings, rms 11.8 percent. stencil_same is 0: every set has
  // the same half stencil (cutoff = 2 bins), so it is one with the
  // packings' constants.
  return LammpsCoefficients{{3.36032e-07, 6.52424e-10, 1.11277e-08, 0, 1.01285e-09, 2.20888e-09, 3.05741e-09}};
}

LammpsTerms lammps_terms(std::span<const double> sorted_diameters, std::span<const double> box,
                         std::span<const double> bounds) {
  const int d = static_cast<int>(box.size());
  const std::size_t L = bounds.size();
  if ((d != 2 && d != 3) || L == 0 || sorted_diameters.empty())
    throw InputError("collections", "a 2D or 3D box, at least one collection and one particle");
  double volume = 1;
  for (double s : box) volume *= s;
  const double ghost = bounds.back();  // ghost cutoff: the largest pair cutoff (zero skin)
  std::vector<double> count(L);
  std::vector<std::array<Axis, 3>> axes(L);
  std::vector<double> per_bin(L);  // particles per bin
  LammpsTerms t;
  t.particles = static_cast<double>(sorted_diameters.size());
  t.lookups = t.particles * static_cast<double>(L);
  std::size_t below = 0;
  for (std::size_t j = 0; j < L; ++j) {
    const auto upto = static_cast<std::size_t>(
        std::upper_bound(sorted_diameters.begin(), sorted_diameters.end(), bounds[j]) - sorted_diameters.begin());
    count[j] = static_cast<double>(upto - below);
    below = upto;
    double cells = 1, bin_volume = 1;
    for (int a = 0; a < d; ++a) {
      axes[j][a] = bins_along(box[a], bounds[j]);
      cells *= axes[j][a].count + 2 * std::ceil(ghost / axes[j][a].side) + 2;
      bin_volume *= axes[j][a].side;
    }
    t.bins += cells;
    per_bin[j] = count[j] * bin_volume / volume;
  }
  for (std::size_t i = 0; i < L; ++i) {
    if (count[i] == 0) continue;
    for (std::size_t j = i; j < L; ++j) {
      const double full = full_stencil(std::span<const Axis>(axes[j].data(), static_cast<std::size_t>(d)),
                                       0.5 * (bounds[i] + bounds[j]));
      if (j == i) {  // half: the upper half of the stencil and the own bin, whose list is walked whole
        t.stencil_same += count[i] * (0.5 * (full - 1) + 1);
        t.checks_same += count[i] * (0.5 * (full - 1) + 1) * per_bin[j];
      } else {
        t.stencil_cross += count[i] * full;
        t.checks_cross += count[i] * full * per_bin[j];
      }
    }
  }
  return t;
}

double lammps_seconds(const LammpsCoefficients& c, const LammpsTerms& t) {
  const auto v = t.as_array();
  double s = 0;
  for (int k = 0; k < kLammpsTerms; ++k) s += c.c[static_cast<std::size_t>(k)] * v[static_cast<std::size_t>(k)];
  return s;
}

LammpsChoice lammps_collections(std::span<const double> sorted_diameters, std::span<const double> box,
                                const LammpsCoefficients& c) {
  if (sorted_diameters.empty() || !(sorted_diameters.front() > 0))
    throw InputError("diameters", "at least one particle, every diameter > 0");
  // In units of the smallest diameter: the search is then the same in any unit.
  const double unit = sorted_diameters.front(), top = sorted_diameters.back() / unit;
  std::vector<double> diam(sorted_diameters.begin(), sorted_diameters.end()), side(box.begin(), box.end());
  for (double& x : diam) x /= unit;
  for (double& x : side) x /= unit;
  LammpsChoice best;
  best.seconds = std::numeric_limits<double>::infinity();
  const auto seconds = [&](const std::vector<double>& bounds) {
    ++best.evaluations;
    for (double b : bounds) {
      double bins = 1;
      for (double s : side) bins *= std::floor(s / (0.5 * b)) + 2 * std::ceil(top / (0.5 * b)) + 2;
      if (bins > kLammpsMaxBinsPerCollection) return std::numeric_limits<double>::infinity();
    }
    return lammps_seconds(c, lammps_terms(diam, side, bounds));
  };
  constexpr double kSteps[] = {2.0, 1.4142135623730951, 1.189207115002721, 1.0905077326652577, 1.0442737824274138};
  for (int L = 1; L <= kLammpsMaxCollections; ++L) {
    for (double first : {2.0, 4.0, 8.0, 16.0}) {
      if (L > 1 && !(first < top)) break;
      std::vector<double> s(static_cast<std::size_t>(L), top);
      for (int h = 0; h + 1 < L; ++h) s[h] = first * std::pow(top / first, double(h) / double(L - 1));
      double here = seconds(s);
      detail::coordinate_search(s, here, 1.0, kSteps, seconds);
      if (here < best.seconds) best.seconds = here, best.bounds = s;
      if (L == 1) break;
    }
  }
  for (double& b : best.bounds) b *= unit;
  best.bounds.back() = sorted_diameters.back();
  return best;
}

}  // namespace hgrid
