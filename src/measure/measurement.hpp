// One measurement of the HGrid on one packing: the counted search, its
// per-level tables, T/N, the sizes as used and, when asked, the cost models'
// predictions, the occupancy of the lowest level, uncounted timings and the
// time model's seconds. Every command, scene, binding and benchmark that
// measures a grid calls measure(); every report of it is written from the
// one table of its fields (measure/fields.hpp).
#pragma once
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hgridlab/grid/counters.hpp"
#include "hgridlab/grid/params.hpp"
#include "hgridlab/model/excluded.hpp"
#include "hgridlab/model/time_model.hpp"
#include "hgridlab/packing/packing.hpp"

namespace hgrid {

/// Uncounted runs: at least min_repeats and until min_seconds of query time
/// have passed, at most max_repeats.
struct TimingOptions {
  int min_repeats = 3;
  int max_repeats = 50;
  double min_seconds = 0.2;
};

/// Which predictions a measurement adds beside its counts: none, the
/// paper's model (random centres), or the paper's and the excluded-volume
/// model (hard spheres; the slow one, 1-6 s at N = 10^5 in 3D).
enum class Predictions { none, paper, excluded };
/// "none" | "paper" | "excluded"; anything else throws InputError naming `field`.
Predictions parse_predictions(const std::string& s, const std::string& field = "model");

/// What to measure beside the counts (all off: the counted search alone).
struct MeasureOptions {
  double K = 0.2;                  // T = narrow-phase checks + K cell accesses (Eq. 27)
  bool model = false;              // the paper's model (random centres) for the sizes used
  bool excluded_model = false;     // with model: the excluded-volume model too (hard spheres)
  void predict(Predictions p) {
    model = p != Predictions::none;
    excluded_model = p == Predictions::excluded;
  }
  bool model_progress = false;     // a long 2D excluded-volume solution reports on stderr
  double excluded_work_budget = 0;  // 2D: the most multiply-adds of its solution (ExcludedOptions; 0: none)
  WallPairs wall_pairs = WallPairs::depleted_layer;  // walls: the excluded-volume model's pairs near a wall
  bool occupancy = false;          // share of lowest-level cells holding >= 2 particles
  std::optional<TimingOptions> timing;  // also time uncounted build + query runs, keep the fastest
  /// The time model's coefficients (one thread) and where they come from:
  /// predicted seconds for the sizes used, from the model's expected terms
  /// and from the counted ones.
  std::optional<TimeCoefficients> time_model;
  std::string time_model_source;
};

/// A value not measured is NaN (numbers) or empty (lists, text): reports
/// write null.
struct Measurement {
  // The packing.
  std::uint64_t n = 0;
  int d = 3;
  Boundary boundary = Boundary::periodic;
  bool boundary_assumed = false;  // the file had no boundary: periodic assumed
  double nu_achieved = 0;         // packing fraction of the particles in their box
  std::vector<double> tilt;       // a tilted box's xy (2D), xy xz yz (3D); empty: orthogonal
  double tilt_inflation = NAN;    // a tilted box's c (grid/tilted.hpp)
  // The grid.
  Search search = Search::top_down;
  int threads = 1;                     // threads the counted search ran on
  double K = 0.2;
  std::vector<double> sizes_requested;  // cell sizes asked for
  std::vector<double> sizes;            // cell sizes used (merged, fitted to a periodic box)
  Counters counts;                      // the counted search
  BuildWork build_work;                 // what its build did (terms of the time model)
  double T_over_N = 0, T_cd_over_N = 0, T_ca_over_N = 0;
  // The paper's model for the same radii, packing fraction and sizes.
  double model_T_over_N = NAN, model_T_cd_over_N = NAN, model_T_ca_over_N = NAN;
  std::vector<double> model_checks_by_level;  // L x L expected checks (counts, like checks_by_level)
  std::string model_skipped;                  // why it was not computed ("" when it was or was not asked)
  // The excluded-volume model, where it applies.
  double model_excluded_T_over_N = NAN, model_excluded_T_cd_over_N = NAN, model_excluded_T_ca_over_N = NAN;
  std::vector<double> model_excluded_checks_by_level;
  std::string model_excluded_skipped;  // why it was not computed ("" when it was or was not asked)
  std::optional<WallPairs> wall_pairs;  // walls with the excluded-volume model: its pairs near a wall
  double share_multi_lowest = NAN;
  // Wall time of the counted build and query.
  double seconds_build = 0, seconds_query = 0;
  // Uncounted runs (MeasureOptions::timing): what a simulation runs.
  int repeats = 0;
  double seconds_build_best = NAN, seconds_query_best = NAN, seconds_query_median = NAN;
  // The time model (one thread).
  std::string time_model;
  double predicted_seconds_build_one_thread = NAN, predicted_seconds_query_one_thread = NAN;
  double predicted_seconds_build_one_thread_from_counts = NAN, predicted_seconds_query_one_thread_from_counts = NAN;
};

/// Sets the counts of a search of m.n particles and the work per particle
/// they give at weight K (T_over_N, T_cd_over_N, T_ca_over_N; 0 for n = 0):
/// what measure() records, and the decomposed search its gathered counts.
void record_counts(Measurement& m, Counters c, double K);

/// Builds the grid of `g` on `p`, runs one counted search and what `o` asks.
/// Throws InputError for an empty packing or sizes the grid refuses.
Measurement measure(const Packing& p, const GridParams& g, const MeasureOptions& o = {});

}  // namespace hgrid
