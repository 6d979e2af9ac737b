// The packing type: its packing fraction and its validation.

#include "hgridlab/packing/packing.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <tuple>

#include "hgridlab/base/error.hpp"

namespace hgrid {

double Packing::packing_fraction() const {
  double vol = 0;
  for (double r : radii) vol += ball_volume(d, r);
  double box_vol = 1;
  for (int a = 0; a < d; ++a) box_vol *= box[a];
  return vol / box_vol;
}

void validate(Packing& p, std::uint64_t first_index) {
  if (p.d != 2 && p.d != 3) throw InputError("d", "must be 2 or 3 (got " + std::to_string(p.d) + ")");
  for (int a = 0; a < p.d; ++a)
    if (!(std::isfinite(p.box[a]) && p.box[a] > 0))
      throw InputError("box", "side " + std::to_string(a + 1) + " must be finite and > 0");
  if (p.tilted()) {
    if (p.boundary != Boundary::periodic) throw InputError("box", "a tilted box must be periodic");
    p.d == 2 ? p.tilted_box<2>().check() : p.tilted_box<3>().check();  // finite tilts, xz = yz = 0 in 2D
  }
  if (p.positions.size() != p.radii.size() * static_cast<std::size_t>(p.d))
    throw InputError("positions", "expected " + std::to_string(p.radii.size()) + " x " + std::to_string(p.d) +
                                      " values, got " + std::to_string(p.positions.size()));
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!(std::isfinite(p.radii[i]) && p.radii[i] > 0))
      throw InputError("radius", "particle " + std::to_string(i + first_index) + " has radius " + std::to_string(p.radii[i]) +
                                     " (must be finite and > 0)");
    if (!std::isfinite(ball_volume(p.d, p.radii[i])))
      throw InputError("radius", "particle " + std::to_string(i + first_index) + " has radius " + std::to_string(p.radii[i]) +
                                     " (its volume overflows)");
    for (int a = 0; a < p.d; ++a) {
      double& x = p.positions[i * p.d + a];
      if (!std::isfinite(x))
        throw InputError("position", "particle " + std::to_string(i + first_index) + " has a non-finite coordinate");
      if (p.tilted()) {
        continue;  // wrapped below, in fractional coordinates
      } else if (p.boundary == Boundary::periodic) {
        x = detail::wrap(x, p.box[a]);
      } else if (x < 0 || x > p.box[a]) {
        throw InputError("position", "particle " + std::to_string(i + first_index) + " has its centre outside the walled box [0, " +
                                         std::to_string(p.box[a]) + "] on axis " + std::to_string(a + 1));
      }
    }
  }
  if (p.tilted()) {
    const auto into_cell = [&](auto box) {
      constexpr int D = std::tuple_size_v<decltype(box.length)>;
      for (std::size_t i = 0; i < p.size(); ++i) {
        std::array<double, D> x{};
        for (int a = 0; a < D; ++a) x[a] = p.positions[i * D + a];
        std::array<double, D> s = box.fractional(x);
        for (auto& v : s) v = detail::wrap(v, 1.0);
        x = box.cartesian(s);
        for (int a = 0; a < D; ++a) p.positions[i * D + a] = x[a];
      }
    };
    if (p.d == 2) into_cell(p.tilted_box<2>());
    else into_cell(p.tilted_box<3>());
  }
  if (!std::isfinite(p.packing_fraction()))
    throw InputError("radius", "the particles' volume over the box's is not a finite number (radii too large)");
}

std::uint64_t available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::uint64_t kb = 0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024;
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : UINT64_MAX;
}

void check_memory(const std::string& field, std::uint64_t n, double bytes_per_particle, const std::string& what) {
  auto gib = [](double b) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g GiB", b / (1024.0 * 1024.0 * 1024.0));
    return std::string(buf);
  };
  if (n > kMaxParticles)
    throw InputError(field, std::to_string(n) + " particles is more than the " + std::to_string(kMaxParticles) +
                                " a packing can hold");
  const double need = static_cast<double>(n) * bytes_per_particle;
  const double have = static_cast<double>(available_memory_bytes());
  if (need > have)
    throw InputError(field, what + " of " + std::to_string(n) + " particles needs about " + gib(need) +
                                "; this machine has " + gib(have) + " available");
}

}  // namespace hgrid
