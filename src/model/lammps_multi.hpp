// A cost model of LAMMPS's `neighbor multi` list build with size collections
// (`neigh_modify collection/interval c_1 ... c_L`, granular pair styles), to
// choose the collection bounds a user pastes (docs/MODEL.md section 11).
//
// It follows what LAMMPS (2021 multi rework; Shire, Hanley & Stratford,
// Comp. Part. Mech. 8 (2021)) does per build: collection h holds the
// particles of diameter in (c_{h-1}, c_h]; its bins have side ~c_h / 2 over
// the box and its ghost layer, every bin head is cleared; each particle of
// collection i looks up its bin in every collection, and searches every
// collection j with c_j >= c_i: a half stencil of its own bins (j = i) or a
// full stencil of j's bins (j larger), the bins whose nearest point lies
// within the pair cutoff (c_i + c_j) / 2, each bin a linked list of particles
// checked one by one. The terms are expectations for uniformly spread
// centres; their machine costs are fitted on training packings
// (advice/lammps_fit.hpp, bench/lammps_model.cpp).
#pragma once
#include <array>
#include <span>
#include <vector>

namespace hgrid {

inline constexpr int kLammpsTerms = 7;

/// The terms of one neighbour-list build, as counts for the whole packing.
struct LammpsTerms {
  double particles = 0;      // N: binning, the per-particle loop
  double bins = 0;           // bin heads cleared: all collections, box plus ghost layer
  double lookups = 0;        // N L: a particle's bin in every collection
  double stencil_same = 0;   // bins visited in the particle's own collection (half stencil)
  double stencil_cross = 0;  // bins visited in larger collections (full stencils)
  double checks_same = 0;    // particles met in those bins (linked lists walked, distances tested)
  double checks_cross = 0;
  std::array<double, kLammpsTerms> as_array() const {
    return {particles, bins, lookups, stencil_same, stencil_cross, checks_same, checks_cross};
  }
};

/// Seconds per term (one thread, one MPI rank).
struct LammpsCoefficients {
  std::array<double, kLammpsTerms> c{};
};

/// The coefficients fitted on this project's training packings with
/// Debian's LAMMPS (7 Jan 2022) on the development VM (Intel Xeon); the
/// choice of bounds depends on their ratios only.
LammpsCoefficients default_lammps_coefficients();

/// The terms for collection bounds `bounds` (increasing, the last >= the
/// largest diameter) of particles with `sorted_diameters` (ascending) in a
/// box of sides `box` (2 or 3 of them: the dimension), periodic.
LammpsTerms lammps_terms(std::span<const double> sorted_diameters, std::span<const double> box,
                         std::span<const double> bounds);

double lammps_seconds(const LammpsCoefficients& c, const LammpsTerms& t);

/// LAMMPS's bins per collection are capped (its "Too many neighbor bins"):
/// bounds needing more are not considered.
inline constexpr double kLammpsMaxBinsPerCollection = 2147483647.0;

/// Most collections tried.
inline constexpr int kLammpsMaxCollections = 8;

struct LammpsChoice {
  std::vector<double> bounds;  // c_1..c_L, the last = the largest diameter
  double seconds = 0;          // lammps_seconds at them
  int evaluations = 0;
};

/// The bounds with the least predicted time: for each L up to
/// kLammpsMaxCollections, a coordinate search over c_1..c_{L-1} (factors
/// 2, 2^1/2, ..., 2^1/16) from geometric sets starting at 2, 4, 8 and 16
/// times the smallest diameter. Deterministic; scale-free (the same
/// diameters and box in another unit give the same bounds in that unit).
LammpsChoice lammps_collections(std::span<const double> sorted_diameters, std::span<const double> box,
                                const LammpsCoefficients& c);

}  // namespace hgrid
