// Running a scene: packings -> counted HGrid search -> model, one row per point.
#pragma once
#include <string>
#include <vector>

#include "grid/counters.hpp"
#include "experiment/scene.hpp"

namespace hgrid {

/// Measured and predicted work of one point. Model and occupancy fields are
/// NaN when the scene does not record them.
struct PointResult {
  ScenePoint point;
  std::size_t n = 0;
  double nu_achieved = 0;
  std::vector<double> sizes;  // cell sizes used (fitted to a periodic box)
  Counters counts;
  double T_over_N = 0, T_cd_over_N = 0, T_ca_over_N = 0;
  double model_T_over_N = 0, model_T_cd_over_N = 0, model_T_ca_over_N = 0;
  // The excluded-volume model (excluded placement, 3D; NaN otherwise).
  double model_excluded_T_over_N = 0, model_excluded_T_cd_over_N = 0, model_excluded_T_ca_over_N = 0;
  double share_multi_lowest = 0;  // lowest-level cells with >= 2 particles / all its cells
  double seconds_packing = 0, seconds_sizes = 0, seconds_build = 0, seconds_query = 0;
};

struct RunOptions {
  std::string results_dir = "results";
  std::string packing_dir = "results/packings";
  int jobs = 1;
  bool progress = true;  // progress lines on stderr
};

/// Measures one point (generating or reusing its packing).
PointResult run_point(const Scene& scene, const ScenePoint& point, const RunOptions& opt);

/// Runs every point of the scene and writes <results_dir>/<name>[-<scale>].h5
/// and .csv (the default scale has no suffix). Points already measured by an
/// interrupted run of the same scene and scale are reused from its journal.
std::vector<PointResult> run_scene(const Scene& scene, const RunOptions& opt);

/// Path of the result files without extension.
std::string result_stem(const Scene& scene, const RunOptions& opt);

/// JSON summary of a run (scene, scale, result file, every point), indented.
std::string results_json(const Scene& scene, const std::vector<PointResult>& results, const RunOptions& opt);

}  // namespace hgrid
