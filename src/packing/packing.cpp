// The packing type: its packing fraction and its validation.

#include "packing/packing.hpp"

#include <cmath>
#include <string>

#include "grid/error.hpp"

namespace hgrid {

double Packing::packing_fraction() const {
  double vol = 0;
  for (double r : radii) vol += ball_volume(d, r);
  double box_vol = 1;
  for (int a = 0; a < d; ++a) box_vol *= box[a];
  return vol / box_vol;
}

void validate(Packing& p) {
  if (p.d != 2 && p.d != 3) throw InputError("d", "must be 2 or 3 (got " + std::to_string(p.d) + ")");
  for (int a = 0; a < p.d; ++a)
    if (!(std::isfinite(p.box[a]) && p.box[a] > 0))
      throw InputError("box", "side " + std::to_string(a + 1) + " must be finite and > 0");
  if (p.positions.size() != p.radii.size() * static_cast<std::size_t>(p.d))
    throw InputError("positions", "expected " + std::to_string(p.radii.size()) + " x " + std::to_string(p.d) +
                                      " values, got " + std::to_string(p.positions.size()));
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!(std::isfinite(p.radii[i]) && p.radii[i] > 0))
      throw InputError("radius", "particle " + std::to_string(i) + " has radius " + std::to_string(p.radii[i]) +
                                     " (must be finite and > 0)");
    for (int a = 0; a < p.d; ++a) {
      double& x = p.positions[i * p.d + a];
      if (!std::isfinite(x))
        throw InputError("position", "particle " + std::to_string(i) + " has a non-finite coordinate");
      if (p.boundary == Boundary::periodic) {
        x = detail::wrap(x, p.box[a]);
      } else if (x < 0 || x > p.box[a]) {
        throw InputError("position", "particle " + std::to_string(i) + " has its centre outside the walled box [0, " +
                                         std::to_string(p.box[a]) + "] on axis " + std::to_string(a + 1));
      }
    }
  }
}

}  // namespace hgrid
