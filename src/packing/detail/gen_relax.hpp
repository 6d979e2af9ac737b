// Growth of all radii with FIRE relaxation of a harmonic overlap energy:
// reaches packing fractions where random sequential addition stalls.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hgridlab/packing/detail/gen_common.hpp"
#include "hgridlab/grid/geometry.hpp"

namespace hgrid::detail {

/// Radius growth factor per growth step (2 %). FIRE needs about as many
/// steps after a 2 % growth step as after a 0.5 % one (its relaxation time,
/// not the size of the push, sets the count), so four times fewer growth
/// steps take ~2.4x fewer FIRE steps (N = 10^5, nu = 0.6, alpha = -3, omega =
/// 10, walls: 2674 against 9024; docs/PERFORMANCE.md round 25). Equilibrated
/// afterwards, the packings' T/N is unchanged within the seeds' spread.
inline constexpr double kGrowthStep = 1.02;
/// Largest relative overlap overlap / (r_i + r_j) accepted after each growth
/// step (a quarter of the step's growth), and at the end.
inline constexpr double kStepOverlapTol = 5e-3;
inline constexpr double kFinalOverlapTol = 1e-4;
/// FIRE step budget per growth step and in total.
inline constexpr std::uint64_t kFireStepsPerGrowth = 20000;
inline constexpr std::uint64_t kFireStepsTotal = 400000;
/// Verlet skin of the neighbour list, relative to each radius.
inline constexpr double kSkin = 0.25;
/// Spheres per thread below which generate_packing relaxes on fewer threads
/// (a FIRE step on a few thousand spheres is too short to share).
inline constexpr std::size_t kRelaxMinSpheresPerThread = 8192;

struct RelaxStats {
  std::uint64_t fire_steps = 0;
  int growth_steps = 0;
  int list_builds = 0;
  double max_rel_overlap = 0;
};

/// Starts from non-overlapping centres pos (n x d) of spheres of radius
/// scale0 * radii and grows them to radii (scale 1) in steps of kGrowthStep,
/// relaxing with FIRE (Bitzek et al., Phys. Rev. Lett. 97, 170201 (2006);
/// unit masses, unit stiffness) after each step. With walls, spheres also
/// feel a harmonic wall. Returns false (stats say how far it got) when a step
/// budget runs out. Lists, forces and moves run on `threads` threads; the
/// result does not depend on their number.
bool grow_and_relax(int d, Boundary b, const std::array<double, 3>& box, const std::vector<double>& radii,
                    double scale0, int threads, std::vector<double>& pos, Progress& progress, RelaxStats& stats);

}  // namespace hgrid::detail
