// Running a scene: packings -> counted HGrid search -> model, one row per point.
#pragma once
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "hgridlab/measure/measurement.hpp"
#include "hgridlab/scenes/scene.hpp"

namespace hgrid {

/// One point of a scene: its measurement (measure/measurement.hpp; the
/// model and occupancy fields are NaN when the scene does not record them)
/// and what the runner adds.
struct PointResult {
  ScenePoint point;
  Measurement m;
  std::uint64_t equilibration_sweeps = 0;  // Monte Carlo sweeps the packing had (0: none)
  double seconds_packing = 0, seconds_sizes = 0;
};

struct RunOptions {
  std::string results_dir = "results";
  std::string packing_dir = "results/packings";
  int jobs = 1;
  bool progress = true;  // progress lines on stderr
};

/// Measures one point (generating or reusing its packing). `threads`: of
/// the packing's generation (0: the cores shared by opt.jobs jobs); the
/// packing and the counts do not depend on it.
PointResult run_point(const Scene& scene, const ScenePoint& point, const RunOptions& opt, int threads = 0);

/// A rough estimate of the work of generating a packing, for scheduling
/// only (the largest first, so that no long job starts last): n, times more
/// for excluded-volume packings the denser and the wider their sizes
/// (compression by growth + FIRE beyond nu = 0.35, and the Monte Carlo at
/// omega = 50-100, whose large particles' boxes leave one domain per colour,
/// are the slow ones).
double estimated_work(const PackingSpec& s);

/// Runs every point of the scene and writes `<results_dir>/<name>[-<scale>].h5`
/// and .csv (the default scale has no suffix). Points already measured by an
/// interrupted run of the same scene and scale (on any number of MPI ranks)
/// are reused from its journals (scenes/journal.hpp).
std::vector<PointResult> run_scene(const Scene& scene, const RunOptions& opt);

/// Several scenes in one process as if each ran alone (the same result
/// files, journals and resumption), their packings in one pool of opt.jobs
/// workers: a packing that two scenes share is made once, and no core
/// waits for one scene's last packing while another scene has work left.
/// Scenes whose result files would be the same (name and scale) are
/// refused. Results in the scenes' order.
std::vector<std::vector<PointResult>> run_scenes(const std::vector<Scene>& scenes, const RunOptions& opt);

/// The points of `todo` (indices into scene.points) by packing, each group
/// in scene order, the groups in order of their first point: a group goes to
/// one worker, so that its packing is generated (or read) once.
std::vector<std::vector<std::size_t>> group_by_packing(const Scene& scene, const std::vector<std::size_t>& todo);

/// The first point that failed in measure_groups(), and why.
struct PointFailure {
  std::size_t point;  // index into scene.points
  std::exception_ptr error;
  std::size_t scene = 0;  // run_scenes: index of the point's scene
};

/// Measures the points of `groups` into results[i] (sized like
/// scene.points) on opt.jobs threads, a whole group per thread, the groups
/// of the largest estimated_work first, and each packing generated on the
/// cores of the jobs that are still running; appending
/// each finished point to the journal file `journal` (scenes/journal.hpp)
/// and counting them on a progress line named `what`. After a failure no
/// further point is started; the first failure is returned, not thrown.
std::optional<PointFailure> measure_groups(const Scene& scene, const std::vector<std::vector<std::size_t>>& groups,
                                           const RunOptions& opt, const std::string& journal, const std::string& what,
                                           std::vector<PointResult>& results);

/// Path of the result files without extension.
std::string result_stem(const Scene& scene, const RunOptions& opt);

/// JSON summary of a run (scene, scale, result file, every point), indented.
std::string results_json(const Scene& scene, const std::vector<PointResult>& results, const RunOptions& opt);

}  // namespace hgrid
