// A packing: particles in a box, as stored in files and handed to the grids.
#pragma once
#include <array>
#include <map>
#include <string>
#include <vector>

#include "grid/geometry.hpp"

namespace hgrid {

/// Runtime-dimensional particle set. Positions are row-major N x d.
struct Packing {
  int d = 3;
  std::array<double, 3> box{};  // first d entries used
  Boundary boundary = Boundary::periodic;
  std::vector<double> positions;
  std::vector<double> radii;
  /// Extra root attributes carried with the file (generation parameters, seed...).
  std::map<std::string, double> num_attrs;
  std::map<std::string, std::string> str_attrs;

  std::size_t size() const { return radii.size(); }
  /// Total particle volume / box volume.
  double packing_fraction() const;

  template <int D>
  std::vector<Sphere<D>> spheres() const {
    std::vector<Sphere<D>> out(size());
    for (std::size_t i = 0; i < size(); ++i) {
      for (int a = 0; a < D; ++a) out[i].x[a] = positions[i * D + a];
      out[i].r = radii[i];
    }
    return out;
  }
  template <int D>
  Extent<D> extent() const {
    Extent<D> e{};
    for (int a = 0; a < D; ++a) e[a] = box[a];
    return e;
  }
};

/// Checks a packing (d, box, radii > 0, finite values, centres inside a walled
/// box) and wraps periodic centres into [0, A). Throws InputError naming the field.
void validate(Packing& p);

}  // namespace hgrid
