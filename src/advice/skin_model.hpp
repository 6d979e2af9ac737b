// The skin of a contact list chosen by a cost model (beyond the paper;
// docs/CONTACT_LIST.md, "The skin model").
//
// One step of a contact list with pair skin s costs
//   t(s) = (t_grid + t_store(L)) / k(s) + t_test(L) + t_check,
// a build (the grid of the inflated spheres, then the search and storing of
// the candidates) every k(s) steps, and at every step the test of the L(s)
// candidates and the check of the particles' margins. t_store and t_test
// are affine in L (a part per particle, a part per candidate); their two
// coefficients, t_grid, t_check and the steps per build come from what the
// list measured as it ran at two skins s0 < s1. When the two lists' lengths
// are too close to resolve a cost's slope (L(s1) < kResolvedLengths L(s0))
// or it comes out negative, that cost is proportional to L, from s1's
// measurement. The model gives how the terms change with s:
// - L(s): the measured lengths L(s0), L(s1) joined by the shape of the
//   shell: shell(s), the pairs per particle with r_i + r_j <= distance <
//   r_i + r_j + s in a fluid at packing fraction nu: the ideal gas's,
//   B(s) = (nu / (2 <r^d>)) (<(r_i + r_j + s)^d> - <(r_i + r_j)^d>), plus
//   the excess pairs the hard-sphere fluid holds near contact,
//   E (1 - exp(-s / xi)). E is what the compressibility sum rule leaves
//   beyond contact, E = (S(0) - 1 + nu <(r_i + r_j)^d> / <r^d>) / 2, with
//   S(0) = 1 / (d(nu Z)/d nu) of the equation of state (Carnahan-Starling in
//   3D, Henderson in 2D); xi makes the shell grow at contact as the pair
//   density at contact g_c of that fluid says, E / xi = (g_c - 1) B'(0). So
//   a thin shell holds g_c times the ideal gas's pairs and a thick one the
//   ideal gas's plus E: nothing in it is fitted;
// - k(s) = k(s0) s / s0: between builds the particles move on straight
//   lines (ballistic), and a build comes when the two largest displacements
//   add up to the skin. A list rebuilt at (nearly) every step
//   (k(s0) < kCensoredSteps) says only that a step moves particles farther
//   than s0; there the displacements' growth is measured instead: v, the
//   margin its builds found used up per step (the two largest
//   displacements' sum, even beyond the skin), and g, how much that sum
//   grows from one step to two (travel_growth: 2 on straight lines, sqrt 2
//   in a random walk, as Monte Carlo sweeps move particles). With the
//   displacements growing as t^b, b = log2 g held in [1/2, 1] (between a
//   random walk and straight lines; ballistic when g is unknown),
//   k(s) = (s / v)^(1/b).
#pragma once
#include <vector>

#include "hgridlab/model/distribution.hpp"

namespace hgrid {

/// Two measured lists resolve the slope of a cost in the list's length when
/// the longer is at least this many times the shorter.
inline constexpr double kResolvedLengths = 1.25;

/// A measurement with fewer steps per build than this rebuilt at nearly
/// every step: its steps per build bound the motion from below only, and
/// the travel per step it measured sets k(s).
inline constexpr double kCensoredSteps = 2.0;

/// The exponent b of the displacements' growth (t^b) that a measured
/// travel_growth g gives, log2 g, held in [kRandomWalkExponent, 1]: between
/// a random walk and straight lines.
inline constexpr double kRandomWalkExponent = 0.5;

/// The pair density at contact of the equal-size hard-sphere fluid at
/// packing fraction nu: (1 - nu/2) / (1 - nu)^3 (3D, Carnahan-Starling),
/// (1 - 7 nu / 16) / (1 - nu)^2 (2D, Henderson). InputError for d not 2 or 3,
/// nu outside [0, 1).
double contact_value(int d, double nu);

/// The structure factor at zero wave number of the equal-size hard-sphere
/// fluid, 1 / (d(nu Z)/d nu): (1 - nu)^4 / (1 + 4 nu + 4 nu^2 - 4 nu^3 +
/// nu^4) (3D, Carnahan-Starling), (1 - nu)^3 / (1 + nu + 3 nu^2/8 - nu^3/8)
/// (2D, Henderson). InputError for d not 2 or 3, nu outside [0, 1).
double structure_at_zero(int d, double nu);

/// Expected pairs per particle with r_i + r_j <= distance < r_i + r_j + skin
/// (see above), for radii drawn from `radii`.
double shell_pairs_per_particle(const Distribution& radii, int d, double nu, double skin);

/// What a contact list measured over a window of steps at one skin.
struct SkinMeasurement {
  double skin = 0;               // s0 (> 0)
  double steps_per_build = 0;    // k(s0) (>= 1)
  double contacts_per_n = 0;     // contacts per particle
  double candidates_per_n = 0;   // the list's length per particle at s0
  double seconds_grid = 0;       // per build: the grid of the inflated spheres
  double seconds_store = 0;      // per build: the candidate search and storing
  double seconds_test = 0;       // per step: the test of the candidates
  double seconds_check = 0;      // per step: reading positions, the margins
  double travel_per_step = 0;    // the margin its builds found used up, per step (0: unknown)
  /// The two largest displacements' sum over two steps over that over one
  /// (ContactListStats::travel_two / travel_one; 0: unknown): 2 for
  /// straight lines, sqrt(2) for a random walk.
  double travel_growth = 0;
};

struct SkinPrediction {
  double skin = 0;
  double candidates_per_n = 0;
  double steps_per_build = 0;
  double seconds_per_step = 0;
};

/// The model's cost of skin s (> 0) from measurements at two skins
/// a.skin != b.skin (InputError naming skin otherwise).
SkinPrediction predict_skin(const SkinMeasurement& a, const SkinMeasurement& b, const Distribution& radii, int d,
                            double nu, double skin);

/// The skin in [lo, hi] (radii's unit) of least predicted seconds per step,
/// from a log-spaced scan of `points` skins refined by golden sections.
SkinPrediction choose_skin(const SkinMeasurement& a, const SkinMeasurement& b, const Distribution& radii, int d,
                           double nu, double lo, double hi, int points = 40);

}  // namespace hgrid
