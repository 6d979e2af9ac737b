// A model of this implementation's wall time (docs/MODEL.md section 9): the
// build and the query as sums of terms that follow how the grid spends its
// time, each term counted exactly by a counted query and predicted by the
// cost model's integrals. The paper's T = checks + K accesses is unchanged;
// this is an addition, with machine coefficients from `hgrid calibrate`.
#pragma once
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "hgridlab/grid/build_work.hpp"
#include "hgridlab/grid/counters.hpp"
#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/model.hpp"

namespace hgrid {

/// The terms of one build + query, as counts for the whole packing.
struct TimeTerms {
  // Query.
  double particles = 0;       // N: the per-particle loop, the emit buffer, the sweep
  double occupied_cells = 0;  // non-empty cells: one half stencil each (13 row runs in 3D)
  double run_checks = 0;      // overlap tests along contiguous runs of sorted particles (own cell, ranges > 4)
  double list_checks = 0;     // overlap tests of candidates gathered from short ranges (<= 4) into a list
  double runs = 0;            // contiguous runs tested: a loop each, its exit a mispredicted branch
  double searches = 0;        // cross-level searches: one box per particle and level searched
  double rows = 0;            // rows of cells walked by those boxes (two rank look-ups each)
  double scanned = 0;         // particles scanned where a box holds more cells than its level particles
  double probes = 0;          // cells looked up one at a time in a hashed (sparse) level's table
  double contacts = 0;        // overlapping pairs found: a mispredicted branch in a run, a callback each
  // Build.
  double level_steps = 0;      // sum over particles of the level index (0-based): the level-of-insertion search
  double sort_passes = 0;      // radix passes over the particles inside their coarse buckets
  double bucket_passes = 0;    // radix passes times coarse buckets (a histogram each)
  double directory_words = 0;  // bitmap words (64 cells each) of the ranked levels: cleared and ranked
  double directory_slots = 0;  // hash-table slots of the hashed levels: cleared and filled
};

inline constexpr int kQueryTerms = 10;
inline constexpr int kBuildTerms = 6;
inline constexpr std::array<std::string_view, kQueryTerms> kQueryTermNames = {
    "particles", "occupied_cells", "run_checks", "list_checks", "runs", "searches", "rows", "scanned", "probes", "contacts"};
inline constexpr std::array<std::string_view, kBuildTerms> kBuildTermNames = {
    "particles", "level_steps", "sort_passes", "bucket_passes", "directory_words", "directory_slots"};
std::array<double, kQueryTerms> query_terms(const TimeTerms& t);
std::array<double, kBuildTerms> build_terms(const TimeTerms& t);

/// Seconds per unit of each term on one machine (fitted by `hgrid calibrate`).
struct TimeCoefficients {
  std::array<double, kQueryTerms> query{};
  std::array<double, kBuildTerms> build{};
};

struct PredictedSeconds {
  double build = 0, query = 0;
  double total() const { return build + query; }
};
PredictedSeconds predict_seconds(const TimeCoefficients& c, const TimeTerms& t);

/// What a build did beyond its particles (HGrid::directory_words(),
/// HGrid::directory_slots(), HGrid::sort_work()).
struct BuildWork {
  std::uint64_t directory_words = 0, directory_slots = 0;
  SortWork sort;
};
template <class Grid>
BuildWork build_work(const Grid& g) {
  return {g.directory_words(), g.directory_slots(), g.sort_work()};
}

/// The terms a counted query and its grid's build measured.
TimeTerms counted_time_terms(const Counters& c, const BuildWork& b);

/// The expected terms for n particles with independent uniform centres in a
/// periodic box (the paper's assumptions) and cell sizes s_1..s_L: occupied
/// cells from Poisson occupancy, checks from the cost model (Eqs. 12-22)
/// split into runs and lists by the Poisson probability that a range holds
/// more than 4 particles, rows from the box extent E[(2 + 2r/s_j)^(d-1)]
/// (Eq. 16 with one axis fewer), and the scan where the expected box b(j,h)
/// holds more cells than level j holds particles (as the grid decides per box);
/// contacts from the overlap volume, n^2 v_d E[(r_i + r_j)^d] / (2 V).
/// box_volume > 0: the particles fill n V_p / nu of a larger box (a bed
/// under empty space; docs/MODEL.md section 14): the cells the build lays
/// out, clears and sorts into (directories, ranked or hashed levels, radix
/// buckets) are the whole box's, the occupancy that of the filled part.
TimeTerms expected_time_terms(const Distribution& dist, const ModelParams& p, const std::vector<double>& sizes,
                              double n, double box_volume = 0);

/// Cell sizes that minimise the predicted seconds of one build + query for
/// n particles: for each L from 1 to the count optimum's L* + 3 (at the K
/// given in p), a coordinate search in ln s_h (steps x1.25, x1.1, x1.03,
/// order kept, s_L = 2 r_max) from the count optimum at that L; the best
/// over L. Returns sizes ready for the grid (collapsed levels merged).
/// box_volume: as expected_time_terms.
struct TimeOptimalSizes {
  std::vector<double> sizes;
  PredictedSeconds seconds;
  int evaluations = 0;
};
TimeOptimalSizes time_optimal_sizes(const Distribution& dist, const ModelParams& p, const TimeCoefficients& c,
                                    double n, double box_volume = 0);

}  // namespace hgrid
