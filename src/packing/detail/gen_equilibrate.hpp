// Hard-sphere equilibration of an excluded-volume packing: erases the memory
// of the insertion order (largest first) without changing nu or the radii.
//
// The paper's packings were "colliding elastic spheres". Event-driven
// dynamics and Metropolis Monte Carlo with hard-core rejection sample the
// same equilibrium ensemble (every non-overlapping configuration equally
// likely); Monte Carlo needs no event calendar, whose collision prediction
// is awkward with omega = 100 (a big sphere meets thousands of small ones),
// and reuses the insertion grid.
//
// Trials: with probability kSwapFraction a swap, two particles exchanging
// their positions (Grigera & Parisi, Phys. Rev. E 63 (2001) 045102; the
// proposal is symmetric, so hard-core rejection alone keeps detailed
// balance); otherwise a uniform displacement of at most kMcStep r_i per axis.
// Either is accepted if it creates no overlap (nor wall contact). Swaps move
// a small particle from one hole between big ones to another, which
// displacements at nu = 0.6 cannot.
//
// On all cores, by checkerboard domains (Anderson, Jankowski, Grubb, Engel &
// Glotzer, J. Comput. Phys. 254 (2013) 27): each sweep shifts a grid of
// domains, each at least a largest diameter wide, by a random origin; the
// 2^d colours of the domains (parity per axis) take turns, and the domains
// of one colour run at once: each makes as many trials as it holds
// particles, drawn among its own, swaps pair two of its own, and a move that
// would leave it is rejected. A sphere centred in a domain reaches no sphere
// of another domain of its colour, so a colour's domains are independent.
// Each draws from its own stream, seeded by (sweep, domain): the packing is
// the same for any number of threads.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hgridlab/packing/detail/gen_common.hpp"
#include "hgridlab/packing/detail/gen_relax.hpp"
#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/packing/generate.hpp"

namespace hgrid::detail {

inline constexpr double kMcStep = 0.2;
/// Share of the trials that are swaps (Ninarello, Berthier & Coslovich,
/// Phys. Rev. X 7 (2017) 021039, use 0.2).
inline constexpr double kSwapFraction = 0.2;

/// Event chains (gen_event_chain.hpp) and their swaps move spheres whose radii are this share
/// smaller than the packing's (2 kFinalOverlapTol): a compressed packing's
/// pairs overlap by up to kFinalOverlapTol of their contact distance, and
/// with overlapping pairs a chain can be passed on without moving, around
/// the box, for ever. The packing's pairs may then overlap by this share;
/// nu for the chains is (1 - kChainShrink)^d nu (T/N changes by ~10^-4).
inline constexpr double kChainShrink = 2 * kFinalOverlapTol;

/// The move lists are made afresh (and the grid's nodes renumbered) at the
/// start of a sweep once more than 1/kRelistUnlistedShare of the spheres
/// have outgrown their lists, or the relists since the last time exceed
/// kRelistPerSphere per sphere (each leaves stale entries behind).
inline constexpr std::size_t kRelistUnlistedShare = 64;
inline constexpr std::size_t kRelistPerSphere = 4;
/// A sweep that relists more than one sphere in kRelistsWorthLists turns
/// the lists off for the rest of the run (at omega = 10, nu = 0.6 from
/// compression ~1 in 70 is relisted per sweep and the lists save 25 %; from
/// sequential addition at omega = 100, 1 in 12, and they cost 14 %).
inline constexpr std::size_t kRelistsWorthLists = 20;

/// Running totals of an equilibration, carried across resumptions (stored
/// as packing attributes): sweeps done and trials by kind.
struct Equilibration {
  std::uint64_t sweeps = 0;
  std::uint64_t moves_accepted = 0, moves_proposed = 0, swaps_accepted = 0, swaps_proposed = 0;
  double displacement_acceptance() const { return ratio(moves_accepted, moves_proposed); }
  double swap_acceptance() const { return ratio(swaps_accepted, swaps_proposed); }

 private:
  static double ratio(std::uint64_t a, std::uint64_t b) {
    return b ? static_cast<double>(a) / static_cast<double>(b) : 0.0;
  }
};

/// Called between sweeps (not after the last), at most every
/// checkpoint_seconds of wall time, with pos and rng as after e.sweeps
/// sweeps: what resuming needs.
using EquilibrationCheckpoint = std::function<void(const Equilibration& e)>;

/// Called after every sweep with pos as after e.sweeps sweeps; returns true
/// to end the run there (before target), and may add to the progress line.
using EquilibrationObserver = std::function<bool(const Equilibration& e, std::string& progress_extra)>;

/// Domains are at least (1 + kDomainMargin) largest diameters wide, so that
/// rounding cannot make a search reach a domain two away.
inline constexpr double kDomainMargin = 1e-6;

/// Runs sweeps until e.sweeps == target or `observe` says stop (e: the
/// totals so far; zero for a fresh start). A sweep draws only from rng and reads only pos, so a run
/// resumed from a checkpoint's pos, rng state and e is the uninterrupted
/// run, bit for bit. `threads` as in base/threads.hpp (0 = all cores); the
/// result does not depend on it.
/// event_chain: the moves of gen_event_chain.hpp (periodic only; one thread)
/// instead of the checkerboard's.
void equilibrate(int d, Boundary b, bool event_chain, const std::array<double, 3>& box, const std::vector<double>& radii,
                 std::vector<double>& pos, std::uint64_t target, int threads, GenRng& rng, Progress& progress,
                 Equilibration& e, const EquilibrationCheckpoint& checkpoint = {}, double checkpoint_seconds = 300,
                 const EquilibrationObserver& observe = {}, OverlapSearch search = OverlapSearch::lists);

}  // namespace hgrid::detail
