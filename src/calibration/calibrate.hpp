// Measuring K on this machine: time the HGrid on a set of calibration scenes
// and fit query wall time W = c0 N + c_cell A + c_test C (A cell accesses,
// C narrow-phase checks, from a counted run of the same search).
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "hgridlab/calibration/calibration.hpp"
#include "hgridlab/packing/generate.hpp"
#include "hgridlab/measure/measurement.hpp"

namespace hgrid {

/// A generated packing and a choice of cell sizes (Top-Down search).
struct CalibrationScene {
  PackingSpec packing;
  std::string cells = "optimal";  // "single" (one level, s = 2 r_max) or a cell-size method
  std::optional<int> levels;      // fixed L, else the method's L*
  double K_sizes = 0.2;           // the K the method chooses the sizes for
  std::string label() const;      // e.g. "3D random a=-3 w=100 nu=0.3 N=1e+05 optimal(K=0.2)"
};

/// The calibration set: 2D and 3D, random and excluded-volume centres,
/// alpha = -3 and 0, omega 2..100, and per packing several cell sizes (one
/// level, optimal for K = 0.02..5, linear/exponential with many levels), so
/// that accesses and checks vary independently. `quick`: fewer, smaller.
std::vector<CalibrationScene> calibration_scenes(bool quick);

/// Packings not used in the fit (other seeds, alpha, omega, nu, boundaries),
/// each with a few cell sizes: the time model's predictions are judged here.
std::vector<CalibrationScene> holdout_scenes(bool quick);

struct CalibrationSample {
  CalibrationScene scene;
  std::size_t n = 0;
  int levels = 0;                  // levels actually used
  std::uint64_t accesses = 0, checks = 0, contacts = 0;
  double seconds = 0;              // fastest uncounted query
  double build_seconds = 0;        // fastest build of the grid
  int repeats = 0;
  TimeTerms terms;                 // the time model's terms, counted
  bool holdout = false;            // measured, not fitted
};

/// Cell sizes of a scene for its packing.
std::vector<double> scene_sizes(const CalibrationScene& s, const Packing& p);

/// Counts and times one scene on its (already generated) packing.
CalibrationSample measure_scene(const CalibrationScene& s, const Packing& p, const TimingOptions& opt);

/// K = a / b and its standard error by first-order propagation:
/// var K = K^2 (var_a / a^2 + var_b / b^2 - 2 cov_ab / (a b)).
struct Ratio {
  double value = 0, err = 0;
};
Ratio ratio_with_error(double a, double b, double var_a, double var_b, double cov_ab);

/// Least squares of W = c0 N + c_cell A + c_test C over the samples, on
/// relative residuals (each row divided by its W: timing noise grows with the
/// time and the scenes span decades). Standard errors from the covariance
/// scaled by the residual variance; R^2 of W itself. Needs >= 4 samples.
/// Fills the fit fields only (no provenance).
Calibration fit_calibration(const std::vector<CalibrationSample>& samples);

/// The time model's coefficients (model/time_model.hpp) for dimension d,
/// query and build separately, by non-negative least squares on relative
/// residuals over that dimension's samples not marked holdout; its quality
/// on those and on the holdout ones.
TimeModelFit fit_time_model(const std::vector<CalibrationSample>& samples, int d);

/// Quality of predictions against measurements (both > 0).
FitQuality fit_quality(const std::vector<double>& predicted, const std::vector<double>& measured);

struct CalibrateOptions {
  bool quick = false;
  bool holdout = true;  // also measure the held-out scenes (not fitted)
  TimingOptions timing;
  /// Every scene is timed once per pass, the passes one after the other, and
  /// the fastest time is kept: a burst of load from other processes then
  /// hits one pass of a scene, not all its repeats.
  int passes = 2;
  /// Called after each scene and pass with (timings done, total, the sample).
  std::function<void(std::size_t, std::size_t, const CalibrationSample&)> progress;
};

struct CalibrationRun {
  Calibration result;  // fit and provenance (machine, date, git hash, compiler)
  std::vector<CalibrationSample> samples;
};

/// Generates the packings (kept in memory), measures every scene, fits.
CalibrationRun run_calibration(const CalibrateOptions& opt);

}  // namespace hgrid
