// The machine's measured K (cell access time / overlap test time): the record
// `hgrid calibrate` stores, where it lives, and `K = auto`.
#pragma once
#include <string>

namespace hgrid {

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

/// "model name" of /proc/cpuinfo, or "unknown".
std::string machine_description();

}  // namespace hgrid
