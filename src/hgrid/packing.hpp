// A packing: particles in a box, as stored in files and handed to the grids.
#pragma once
#include <array>
#include <map>
#include <string>
#include <vector>

#include "hgrid/geometry.hpp"

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

/// "periodic" or "walls"; throws InputError("boundary", ...) otherwise.
Boundary parse_boundary(const std::string& s);

/// Checks a packing (d, box, radii > 0, finite values, centres inside a walled
/// box) and wraps periodic centres into [0, A). Throws InputError naming the field.
void validate(Packing& p);

/// Reads a packing: HDF5 (.h5, .hdf5) or CSV (.csv), then validates it.
Packing read_packing(const std::string& path);

/// Writes a packing as HDF5 (datasets /positions, /radii; root attributes d,
/// box, boundary, the packing's own attributes, git hash and compiler). The
/// file is written under a temporary name and renamed, so no partial file is
/// ever left at `path`.
void write_packing(const std::string& path, const Packing& p);

/// Provenance strings recorded in every file hgridlab writes.
const char* git_hash();
const char* compiler_id();

}  // namespace hgrid
