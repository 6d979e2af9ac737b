// Packing generators: radii drawn from a size distribution, a box
// sized for an exact packing fraction, and centres placed either at random
// (the cost model's assumption, docs/MODEL.md section 3) or with excluded volume
// (the paper's measured packings, figures 11-12).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "hgridlab/model/distribution.hpp"
#include "hgridlab/packing/packing.hpp"

namespace hgrid {

// ---- the experiments' interface ------------------------------------------

/// Where centres go: independent uniform centres; excluded volume (no
/// overlaps); or a bed: excluded volume, then every sphere settled under
/// gravity onto the floor (the last axis) of a box walled on every axis
/// (packing/detail/gen_relax.hpp, settle_under_gravity), the box's nu
/// being the particles' volume over the whole box.
enum class Placement { random, excluded, bed };

inline const char* to_string(Placement p) {
  return p == Placement::random ? "random" : p == Placement::excluded ? "excluded" : "bed";
}
/// Excluded volume: placement excluded or bed.
inline bool excludes_volume(Placement p) { return p != Placement::random; }
/// "random" | "excluded" | "bed"; anything else throws InputError naming `field`.
Placement parse_placement(const std::string& s, const std::string& field = "placement");

/// How excluded-volume placement reaches nu: largest-first random sequential
/// addition, falling back to growth where it stalls (automatic); sequential
/// addition only (refused where it stalls); or always growth: sequential
/// addition at nu = 0.35 (or nu if lower), then all radii grown with FIRE
/// relaxation to nu.
enum class ExcludedMethod { automatic, rsa, growth };
/// "auto" | "rsa" | "growth"; anything else throws InputError naming `field`.
ExcludedMethod parse_excluded_method(const std::string& s, const std::string& field = "method");
inline const char* to_string(ExcludedMethod m) {
  return m == ExcludedMethod::automatic ? "auto" : m == ExcludedMethod::rsa ? "rsa" : "growth";
}

/// When an equilibration ends: after its sweeps, or as soon as the packing's
/// T/N (optimal Top-Down sizes for its radii, K = 0.2: the figures' counted
/// work) is stationary within its noise (packing/detail/gen_stationary.hpp),
/// the sweeps then being a cap.
enum class EquilibrationStop { sweeps, stationary };
/// "sweeps" | "stationary"; anything else throws InputError naming `field`.
EquilibrationStop parse_equilibration_stop(const std::string& s, const std::string& field = "stop");
inline const char* to_string(EquilibrationStop s) { return s == EquilibrationStop::sweeps ? "sweeps" : "stationary"; }
/// The moves of an equilibration: the checkerboard Metropolis Monte Carlo
/// (displacements and swaps, on all cores; packing/detail/gen_equilibrate.hpp)
/// or event chains with the same swaps (one thread, periodic boxes;
/// packing/detail/gen_event_chain.hpp). Both sample the equilibrium of hard
/// spheres; they reach it at different costs.
enum class EquilibrationMoves { metropolis, event_chain };
/// "metropolis" | "event-chain"; anything else throws InputError naming `field`.
EquilibrationMoves parse_equilibration_moves(const std::string& s, const std::string& field = "moves");
inline const char* to_string(EquilibrationMoves m) {
  return m == EquilibrationMoves::metropolis ? "metropolis" : "event-chain";
}
/// How the Metropolis trials' overlap tests find the spheres they may meet:
/// on each sphere's move list where that is exact (Verlet lists;
/// packing/detail/gen_move_lists.hpp), or always on the insertion grid. The
/// packing does not depend on it (tests compare the two bit for bit); `grid`
/// is the test the lists replaced, kept for tests and benchmarks.
enum class OverlapSearch { lists, grid };
/// The observable of EquilibrationStop::stationary: K and search of its T/N.
inline constexpr double kStationaryK = 0.2;
/// Largest drift of T/N per doubling of the run, widened by two standard
/// errors, relative to T/N, that counts as stationary (0.1 %; the figures
/// ask their T/N within 0.5 %).
inline constexpr double kStationaryRelTol = 1e-3;

/// Everything that determines a generated packing (and its cache key).
/// Monte Carlo sweeps of an equilibration unless a spec says otherwise.
inline constexpr int kDefaultEquilibrationSweeps = 20;
inline constexpr int kMaxEquilibrationSweeps = 10000000;

struct PackingSpec {
  int d = 3;
  std::size_t n = 0;
  double nu = 0.3;                 // total particle volume / box volume
  std::string dist = "powerlaw";   // "powerlaw" | "lognormal"
  double alpha = -3, omega = 100;  // power-law exponent; r_max / r_min (r_min = 1)
  double sigma = 0.5;              // lognormal: sigma of ln r (median at sqrt(omega))
  Boundary boundary = Boundary::periodic;
  Placement placement = Placement::random;
  ExcludedMethod method = ExcludedMethod::automatic;  // excluded placement only
  std::uint64_t seed = 1;
  bool equilibrate = false;  // excluded only: hard-sphere equilibration after placement
  int sweeps = kDefaultEquilibrationSweeps;  // equilibrate: Monte Carlo sweeps (n trials each); the cap with stop = stationary
  EquilibrationStop stop = EquilibrationStop::sweeps;  // equilibrate: when it ends
  EquilibrationMoves moves = EquilibrationMoves::metropolis;  // equilibrate: its moves
  double stationary_tol = kStationaryRelTol;  // stop = stationary: the test's tolerance, in (0, 0.1]
  int threads = 0;           // excluded: threads of sequential addition, growth + FIRE and equilibration (base/threads.hpp);
                             // the packing does not depend on it
  OverlapSearch overlap_search = OverlapSearch::lists;  // Metropolis moves' overlap tests; the packing does not depend on it
  bool progress = true;      // progress lines on stderr for long generations
  double checkpoint_seconds = 300;  // equilibrate: least wall time between checkpoints (generate_packing)
};

/// The radius distribution a spec names (r_min = 1). Throws InputError.
std::unique_ptr<Distribution> make_distribution(const PackingSpec& spec);

/// Checks everything about a spec that can be checked before generating:
/// ranges, the distribution, the memory generation would need, and (excluded
/// volume) nu against the random close packing estimate. Throws InputError
/// naming the field; returns the estimate.
double check_packing_spec(const PackingSpec& spec);

/// Generates a packing. Radii: inverse-CDF draws (in draw order in the file);
/// box: cubic, sized so the achieved nu equals spec.nu for those radii.
/// Random placement: independent uniform centres (walls: each centre at least
/// its radius from every wall). Excluded placement: largest-first random
/// sequential addition; where that stalls (alpha >= -1 at high nu), addition
/// at a lower nu followed by growth of all radii with FIRE relaxation.
/// Every generation parameter, the achieved nu and quality figures are
/// stored as attributes. Throws InputError for bad or unreachable requests
/// (the message gives the estimate of the highest reachable nu) and for runs
/// that do not converge within their step budget; nothing is written.
///
/// An equilibration can be resumed: every excluded-volume packing records
/// its random generator's state (an equilibrated one also its running
/// totals), and generate_packing(spec, &from) continues `from` (the same
/// spec at fewer or as many sweeps, or its placement: the same spec without
/// equilibration, sweep 0; see resume_mismatch in packing/identity.hpp) to spec.sweeps. The result is the uninterrupted run's,
/// bit for bit. `checkpoint`, if given, receives the packing part-way (its
/// attributes those of the same spec at the sweeps done) at most every
/// spec.checkpoint_seconds of a long equilibration.
using PackingCheckpoint = std::function<void(const Packing& partial)>;
Packing generate_packing(const PackingSpec& spec, const Packing* from = nullptr,
                         const PackingCheckpoint& checkpoint = {});



/// Relative tolerance on the achieved packing fraction of a generated packing.
inline constexpr double kNuRelTol = 1e-12;


/// Random close packing estimate of a size distribution, see rcp.hpp.
double estimate_rcp(int d, const Distribution& dist);

// ---- quality figures --------------------------------------------------------

/// Relative overlaps are overlap / (r_i + r_j); walls count as r_i. A contact is
/// a pair closer than (r_i + r_j)(1 + kContactGap).
inline constexpr double kContactGap = 1e-3;
/// Number of slabs per axis of the homogeneity check.
inline constexpr int kSlabs = 10;
/// Number of size bands (equal shares of particle volume) of the slab check.
inline constexpr int kSizeBands = 3;

struct PackingQuality {
  double nu = 0;
  double max_rel_overlap = 0, mean_rel_overlap = 0;  // mean over overlapping pairs (0 if none)
  std::uint64_t overlapping_pairs = 0;
  double mean_contacts = 0;
  /// Slab packing fraction / mean, worst over slabs and axes: all particles,
  /// and per size band.
  double slab_max_dev = 0;
  std::vector<double> band_slab_max_dev;
  /// The same deviation expected from counting alone: the standard deviation
  /// of a slab's nu / mean if the same particles had independent uniform
  /// centres (each wholly in one slab), sqrt((1 - 1/S) S sum V_i^2) / sum V_i
  /// for S slabs. A few large particles make it large whatever the generator.
  double slab_noise = 0;
  std::vector<double> band_slab_noise;
  /// slab_nu[axis][slab]
  std::vector<std::vector<double>> slab_nu;
  /// Kolmogorov-Smirnov distance of the radii to dist's cdf and its p-value
  /// (-1 when no distribution was given).
  double ks_distance = -1, ks_pvalue = -1;
  std::vector<double> hist_edges, hist_count, hist_expected;  // log-spaced radius bins
};

/// Overlaps and contacts (unless pairs is false: they cost a contact search),
/// slab homogeneity and (with dist) the goodness of fit of the radii.
PackingQuality assess_packing(const Packing& p, const Distribution* dist, bool pairs = true);

/// Distribution recorded in a packing's attributes (dist, alpha, omega,
/// sigma), or nullptr if the file does not say.
std::unique_ptr<Distribution> recorded_distribution(const Packing& p);

// ---- random placement (kept for the benchmarks) ------------------------------

struct RandomSpec {
  int d = 3;
  std::size_t n = 0;
  double nu = 0.3;  // packing fraction: total particle volume / box volume
  Boundary boundary = Boundary::periodic;
  std::uint64_t seed = 1;
};

/// Random placement with any distribution (see generate_packing).
Packing random_packing(const RandomSpec& spec, const Distribution& dist);

}  // namespace hgrid
