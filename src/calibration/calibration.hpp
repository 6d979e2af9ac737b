// The machine's measured K (cell access time / overlap test time): the record
// `hgrid calibrate` stores, where it lives, and `K = auto`.
#pragma once
#include <array>
#include <optional>
#include <string>

#include "hgridlab/model/time_model.hpp"

namespace hgrid {

/// How well predicted seconds follow measured ones over a set of samples:
/// R^2 of ln W, the rms and the largest |predicted / measured - 1|.
struct FitQuality {
  double r2_log = 0, rms_rel = 0, max_rel = 0;
  int points = 0;
};

/// The time model's coefficients (seconds per unit of each term of
/// model/time_model.hpp) fitted on the calibration scenes, with standard
/// errors, its quality there, and on held-out packings not used in the fit.
struct TimeModelFit {
  TimeCoefficients coef;
  TimeCoefficients err;
  FitQuality query, build, total;          // on the calibration scenes
  FitQuality holdout_query, holdout_build, holdout_total;  // on the held-out scenes
};

/// Fit of query wall time W = c0 N + c_cell A + c_test C over the calibration
/// scenes (A cell accesses, C narrow-phase checks; seconds per unit), and
/// K = c_cell / c_test with its propagated standard error.
struct Calibration {
  double K = 0, K_err = 0;
  double c_cell = 0, c_cell_err = 0;
  double c_test = 0, c_test_err = 0;
  double c0 = 0, c0_err = 0;
  double cov_cell_test = 0;  // covariance of c_cell and c_test
  double r2 = 0;             // coefficient of determination of W
  double rms_rel_residual = 0;
  int points = 0;            // calibration scenes fitted
  std::string machine;       // CPU model (/proc/cpuinfo)
  std::string date;          // UTC, ISO 8601
  std::string git_hash, compiler;
  std::string preset;        // "full" or "quick"
  /// log-time R^2 of the single-K fit above (for comparison with the time model).
  double r2_log = 0;
  /// The time model per dimension ([0]: 2D, [1]: 3D); absent in records
  /// written before the time model.
  std::array<std::optional<TimeModelFit>, 2> time;
  const TimeModelFit* time_model(int d) const {
    return (d == 2 || d == 3) && time[d - 2] ? &*time[d - 2] : nullptr;
  }
};

/// $HGRID_CALIBRATION if set and not empty, else
/// ${XDG_CONFIG_HOME:-$HOME/.config}/hgridlab/calibration.json.
std::string calibration_path();

/// Writes the record as JSON (creating the directory), under a temporary
/// name first and then renamed, so a file at `path` is always whole.
void save_calibration(const Calibration& c, const std::string& path);

/// Reads a record. Throws InputError("calibration", ...) naming the path for a
/// missing file, invalid JSON, a missing or non-numeric field, or K not > 0.
Calibration load_calibration(const std::string& path);

/// A K given as text: a number >= 0, or "auto" for the stored calibration.
/// Errors are InputError(field, ...): a bad number, or for "auto" a missing or
/// corrupt calibration (the message names the path and `hgrid calibrate`).
double resolve_K(const std::string& text, const std::string& field);

/// The stored calibration's K; errors as resolve_K("auto", field).
double calibrated_K(const std::string& field);

/// The time model of the stored calibration for dimension d. Throws
/// InputError(field, ...) naming the path and `hgrid calibrate` when there
/// is no calibration, or one from before the time model.
TimeModelFit calibrated_time_model(int d, const std::string& field);

/// A choice of what the cell-size optimiser minimises: the paper's counted
/// cost T, or this machine's predicted seconds.
enum class CostKind { count, time };
/// "count" | "time"; anything else throws InputError(field).
CostKind parse_cost(const std::string& text, const std::string& field = "cost");

/// The stored calibration, if there is a readable one (nullopt otherwise:
/// no file, or not a valid record).
std::optional<Calibration> stored_calibration();

/// "model name" of /proc/cpuinfo, or "unknown".
std::string machine_description();

}  // namespace hgrid
