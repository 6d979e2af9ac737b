// A packing: particles in a box, as stored in files and handed to the grids.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/grid/tilted_box.hpp"

namespace hgrid {

/// Runtime-dimensional particle set. Positions are row-major N x d.
struct Packing {
  int d = 3;
  std::array<double, 3> box{};  // first d entries used
  Boundary boundary = Boundary::periodic;
  /// Tilts xy, xz, yz of a tilted (triclinic) periodic box, LAMMPS's
  /// (grid/tilted_box.hpp; 2D: xy only): all 0 for an orthogonal box.
  std::array<double, 3> tilt{};
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
  bool tilted() const { return tilt[0] != 0 || tilt[1] != 0 || tilt[2] != 0; }
  template <int D>
  TiltedBox<D> tilted_box() const {
    return TiltedBox<D>{extent<D>(), tilt};
  }
  template <int D>
  Extent<D> extent() const {
    Extent<D> e{};
    for (int a = 0; a < D; ++a) e[a] = box[a];
    return e;
  }
};

/// Checks a packing (d, box, tilts, radii > 0, finite values, centres inside
/// a walled box) and wraps periodic centres into [0, A) (a tilted box: into
/// the box's cell, fractional coordinates in [0, 1)). Throws InputError naming the
/// field; particle k is named as k + first_index (a part of a larger file).
void validate(Packing& p, std::uint64_t first_index = 0);

/// The most particles a packing may hold: a grid holds at most 2^31 - 1.
inline constexpr std::uint64_t kMaxParticles = (std::uint64_t{1} << 31) - 1;

/// Peak memory per particle of the heavy steps, measured with bench_generate
/// and bench_hgrid (3D, N = 10^5 to 10^6) and rounded up: reading a packing
/// file, generating a packing (growth + FIRE peaks at ~410 B; random centres
/// at ~41 B, N = 10^7), and building and searching a grid on a packing read
/// from a file.
inline constexpr double kReadBytesPerParticle = 64;
inline constexpr double kGenerateBytesPerParticle = 512;
inline constexpr double kGenerateRandomBytesPerParticle = 64;
inline constexpr double kSearchBytesPerParticle = 256;

/// Memory this process may still use: MemAvailable of /proc/meminfo (else
/// the physical memory), in bytes.
std::uint64_t available_memory_bytes();

/// Refuses, before anything is allocated, work on n particles that needs more
/// memory than the machine has available or more than kMaxParticles: throws
/// InputError(field, ...) with the estimate and what is available.
void check_memory(const std::string& field, std::uint64_t n, double bytes_per_particle, const std::string& what);

}  // namespace hgrid
