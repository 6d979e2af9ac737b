// Hard-sphere equilibration of an excluded-volume packing: erases the memory
// of the insertion order (largest first) without changing nu or the radii.
//
// The paper's packings were "colliding elastic spheres". Event-driven
// dynamics and Metropolis Monte Carlo with hard-core rejection sample the
// same equilibrium ensemble (every non-overlapping configuration equally
// likely); Monte Carlo needs no event calendar, whose collision prediction
// is awkward with omega = 100 (a big sphere meets thousands of small ones),
// and reuses the insertion grid. One sweep proposes n moves, each a uniform
// displacement of at most kMcStep r_i per axis of a random particle,
// accepted if it creates no overlap (nor wall contact).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "packing/detail/gen_common.hpp"
#include "grid/geometry.hpp"

namespace hgrid::detail {

inline constexpr int kEquilibrationSweeps = 20;
inline constexpr double kMcStep = 0.2;

/// Returns the fraction of accepted moves.
double equilibrate(int d, Boundary b, const std::array<double, 3>& box, const std::vector<double>& radii,
                   std::vector<double>& pos, GenRng& rng, Progress& progress);

}  // namespace hgrid::detail
