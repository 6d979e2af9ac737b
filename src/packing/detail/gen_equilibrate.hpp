// Hard-sphere equilibration of an excluded-volume packing: erases the memory
// of the insertion order (largest first) without changing nu or the radii.
//
// The paper's packings were "colliding elastic spheres". Event-driven
// dynamics and Metropolis Monte Carlo with hard-core rejection sample the
// same equilibrium ensemble (every non-overlapping configuration equally
// likely); Monte Carlo needs no event calendar, whose collision prediction
// is awkward with omega = 100 (a big sphere meets thousands of small ones),
// and reuses the insertion grid. One sweep makes n trials. A trial is, with
// probability kSwapFraction, a swap: two particles drawn uniformly exchange
// their positions (Grigera & Parisi, Phys. Rev. E 63 (2001) 045102; the
// proposal is symmetric, so hard-core rejection alone keeps detailed
// balance). Otherwise it is a uniform displacement of at most kMcStep r_i per
// axis of a random particle. Either is accepted if it creates no overlap (nor
// wall contact). Swaps move a small particle from one hole between big ones
// to another, which displacements at nu = 0.6 cannot.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "packing/detail/gen_common.hpp"
#include "grid/geometry.hpp"

namespace hgrid::detail {

inline constexpr double kMcStep = 0.2;
/// Share of the trials that are swaps (Ninarello, Berthier & Coslovich,
/// Phys. Rev. X 7 (2017) 021039, use 0.2).
inline constexpr double kSwapFraction = 0.2;

struct Equilibration {
  double displacement_acceptance = 0;  // accepted / proposed displacements
  double swap_acceptance = 0;          // accepted / proposed swaps
};

Equilibration equilibrate(int d, Boundary b, const std::array<double, 3>& box, const std::vector<double>& radii,
                          std::vector<double>& pos, int sweeps, GenRng& rng, Progress& progress);

}  // namespace hgrid::detail
