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
/// 10, walls: 2674 against 9024; docs/record/PERFORMANCE.md round 25). Equilibrated
/// afterwards, the packings' T/N is unchanged within the seeds' spread.
inline constexpr double kGrowthStep = 1.02;
/// Largest relative overlap overlap / (r_i + r_j) accepted after each growth
/// step (a quarter of the step's growth), and at the end.
inline constexpr double kStepOverlapTol = 5e-3;
inline constexpr double kFinalOverlapTol = 1e-4;
/// FIRE step budget per growth step and in total.
inline constexpr std::uint64_t kFireStepsPerGrowth = 20000;
inline constexpr std::uint64_t kFireStepsTotal = 400000;
/// FIRE's masses: each sphere's stiffness sum (its list pairs' 1/sigma^2,
/// plus its walls'), at least this share of the stiffest sphere's. With unit
/// masses the stiffest sphere sets the time step and the rest relax up to
/// ~7x slower in time (the sums span a factor ~50 at omega = 10); masses
/// equal to the stiffness (a diagonal, Jacobi, preconditioner of the
/// minimisation) give every sphere a period of about one time unit and dt_max
/// = 1. The floor keeps the softest spheres from flying through their skins
/// (uncapped, the lists were rebuilt up to 1.8x as often). N = 10^5, nu = 0.6,
/// omega = 10, one thread: the compression 21.0/22.2 -> 10.0/10.1 s (walls,
/// alpha = 0), 15.5/16.7 -> 10.3/11.4 s (walls, alpha = -3), 10.4/10.1 ->
/// 8.5/8.3 s and 11.0/10.5 -> 9.2/9.3 s (periodic, alpha = 0 and -3);
/// docs/record/PERFORMANCE.md round 38.
inline constexpr double kFireMassFloor = 0.1;
/// Verlet skin of the neighbour list, relative to each radius.
inline constexpr double kSkin = 0.25;
/// Settling (settle_under_gravity): the weights' scale, as the relative
/// overlap the floor's pressure would give a largest sphere resting on it;
/// the net forces' root mean square, relative to the weights', below which
/// the bed has settled (a per-sphere test never ends: the smallest spheres'
/// weights are 1/omega^d of the largest's, below the forces' noise); the
/// FIRE step budget.
inline constexpr double kSettleOverlap = 2e-3;
inline constexpr double kSettleForceTol = 0.05;
inline constexpr std::uint64_t kSettleSteps = 400000;
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
/// unit stiffness, masses as kFireMassFloor says) after each step. With
/// walls, spheres also feel a harmonic wall. Returns false (stats say how
/// far it got) when a step budget runs out. Lists, forces and moves run on
/// `threads` threads; the result does not depend on their number.
bool grow_and_relax(int d, Boundary b, const std::array<double, 3>& box, const std::vector<double>& radii,
                    double scale0, int threads, std::vector<double>& pos, Progress& progress, RelaxStats& stats);

/// A bed: spheres at non-overlapping centres pos (n x d) in a box walled on
/// every axis, each with a weight in proportion to its volume along -x_d,
/// relaxed with FIRE (as grow_and_relax, at full size) until the net
/// forces' root mean square is below kSettleForceTol of the weights'; then
/// the weights removed and the overlaps relaxed below kFinalOverlapTol.
/// Returns false when a step budget runs out.
bool settle_under_gravity(int d, const std::array<double, 3>& box, const std::vector<double>& radii, int threads,
                          std::vector<double>& pos, Progress& progress, RelaxStats& stats);

}  // namespace hgrid::detail
