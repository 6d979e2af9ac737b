// The one scene runner: what is left of a scene (its journals), its packings
// spread over the processes an executor names, each point measured and
// journalled, the result files written by the lead; and what `hgrid run`
// does with scene files, on the same executor. The executor is a
// compile-time policy: LocalRun (this process; run_scene(scene, opt)) or
// mpi::RankRun (the ranks of an MPI run, mpi/sweep.hpp). An executor has
//   int rank() const, int size() const        (0 and 1 here)
//   void collective(F f)                      f on every rank; a failure on one fails all
//   std::string broadcast(const std::string&) rank 0's text on every rank
//   std::vector<std::string> gather(const std::string&)  every rank's text on rank 0
#pragma once
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/atomic_file.hpp"
#include "hgridlab/scenes/dpm_scene.hpp"
#include "hgridlab/scenes/journal.hpp"
#include "hgridlab/scenes/result_files.hpp"
#include "hgridlab/scenes/runner.hpp"

namespace hgrid {

/// One process: every packing measured here (opt.jobs at a time).
struct LocalRun {
  int rank() const { return 0; }
  int size() const { return 1; }
  template <class F>
  void collective(F&& f) { f(); }
  std::string broadcast(const std::string& s) { return s; }
  std::vector<std::string> gather(const std::string& s) { return {s}; }
};

/// The process that measures each of `groups` (group_by_packing): greedy,
/// the largest estimated work first to the process with the least so far.
/// The estimate is n x (points + 1): generating the packing and measuring
/// each point both grow about linearly with n. Ties go to the lower group and
/// process, so that every process computes the same owners.
std::vector<int> assign_groups(const Scene& scene, const std::vector<std::vector<std::size_t>>& groups, int processes);

namespace detail {
/// A failed point as every process's user reads it: the error and which
/// point of the scene it was (an InputError stays one: exit status 2).
[[noreturn]] void rethrow_naming_point(const Scene& scene, const PointFailure& f);
std::string indices_text(const std::vector<std::size_t>& v);
std::vector<std::size_t> indices_from_text(const std::string& s);
}  // namespace detail

/// Every process calls it. The lead (rank 0) reads the journals of
/// interrupted runs and tells the others what is left; each process measures
/// its groups and journals them in its own file (journal_path(stem, rank));
/// the lead gathers the results, writes the result files and removes the
/// journals. A failure anywhere fails everywhere, the failing point named,
/// and writes no result file. Returns the results on the lead (nothing
/// elsewhere).
template <class Exec>
std::vector<PointResult> run_scene(const Scene& scene, const RunOptions& opt, Exec& exec) {
  const bool lead = exec.rank() == 0;
  const std::string stem = result_stem(scene, opt);
  Resumed resumed;
  exec.collective([&] {
    // Every process must sweep the same points: a scene file edited while
    // they were starting would mix two scenes.
    if (exec.broadcast(scene.source) != scene.source)
      throw InputError("SCENE", "the scene file differs from rank 0's (changed while the run started?)");
    std::filesystem::create_directories(opt.results_dir);
    // Temporary files of runs killed before they could remove them.
    for (const auto& dir : {opt.results_dir, opt.packing_dir}) remove_stale_temporaries(dir, kStaleTemporaryAge);
    // The lead alone decides what is left: processes reading the journals
    // themselves could see different files (a shared file system that shows
    // a new file late) and then measure a point twice or never.
    if (lead) resumed = resume(scene, stem, opt.progress);
  });
  const std::vector<std::size_t> todo =
      detail::indices_from_text(exec.broadcast(lead ? detail::indices_text(resumed.todo) : std::string()));
  const auto groups = group_by_packing(scene, todo);
  const std::vector<int> owner = assign_groups(scene, groups, exec.size());
  std::vector<std::vector<std::size_t>> mine;
  for (std::size_t g = 0; g < groups.size(); ++g)
    if (owner[g] == exec.rank()) mine.push_back(groups[g]);

  // The generators' own progress lines from the lead only; every process
  // counts its points on a line of its own.
  Scene local = scene;
  if (!lead)
    for (auto& p : local.points) p.packing.progress = false;
  std::vector<PointResult> measured(scene.points.size());
  exec.collective([&] {
    std::string what = "hgrid run " + scene.name;
    if (exec.size() > 1) what += " [rank " + std::to_string(exec.rank()) + "/" + std::to_string(exec.size()) + "]";
    if (const auto failure = measure_groups(local, mine, opt, journal_path(stem, exec.rank()), what, measured))
      detail::rethrow_naming_point(scene, *failure);
  });

  // One line per point: "<index> <result as JSON>", checked like any input.
  std::string sent;
  for (const auto& g : mine)
    for (std::size_t i : g) sent += std::to_string(i) + ' ' + result_json_line(measured[i]) + '\n';
  const std::vector<std::string> received = exec.gather(sent);
  exec.collective([&] {
    if (!lead) return;
    std::size_t count = 0;
    for (const auto& text : received) {
      std::istringstream in(text);
      for (std::string line; std::getline(in, line); ++count) {
        const std::size_t space = line.find(' ');
        resumed.results.at(std::stoul(line.substr(0, space))) =
            result_from_json_line(line.substr(space + 1), scene.grid.K);
      }
    }
    if (count != todo.size())
      throw std::logic_error("run_scene: " + std::to_string(count) + " results gathered for " +
                             std::to_string(todo.size()) + " points");
    write_results(stem, scene, resumed.results);
    remove_journals(stem);
  });
  return lead ? resumed.results : std::vector<PointResult>{};
}

/// What `hgrid run` does with scene files, at a scale: a DPM scene
/// (kind = "dpm") alone and on one process (scenes/dpm_scene.hpp); else
/// every scene's points, over the executor's processes one scene after the
/// other when it has several, otherwise one scene alone or several in one
/// pool of opt.jobs workers (run_scenes). Each scene and each pair of files
/// written is named on stderr (by the lead). Returns what goes to stdout:
/// with `json` the summary of every point (one scene's object, or an array
/// of them), the DPM scene's summary line without; "" on other processes.
/// Throws InputError for a bad option (jobs < 1) or scene file, and for a
/// DPM scene among others or on several processes.
template <class Exec>
std::string run_scene_files(const std::vector<std::string>& files, const std::string& scale, const RunOptions& opt,
                            bool json, Exec& exec) {
  if (opt.jobs < 1) throw InputError("jobs", "must be >= 1");
  const int processes = exec.size();
  const bool lead = exec.rank() == 0;
  if (files.size() == 1 && scene_kind(files[0]) == "dpm") {
    // One simulation, not a sweep of points: nothing to spread.
    if (processes > 1)
      throw InputError("kind", "a DPM scene (kind = \"dpm\") runs on one process: run it without mpirun");
    return dpm::run_dpm_scene(files[0], scale, opt, json);
  }
  std::vector<Scene> scenes;
  for (const auto& file : files) {
    if (scene_kind(file) == "dpm") throw InputError("SCENE", "a DPM scene runs alone (" + file + ")");
    scenes.push_back(load_scene(file, scale));
    if (lead)
      std::cerr << "hgrid run: scene " << scenes.back().name << " (" << scale << " scale): "
                << scenes.back().points.size() << " points, " << opt.jobs << " job(s)"
                << (processes > 1 ? " on each of " + std::to_string(processes) + " ranks" : "") << "\n";
  }
  // On several processes one scene after the other, each over them all; else one pool.
  std::vector<std::vector<PointResult>> results;
  if (processes > 1 || scenes.size() == 1)
    for (const Scene& s : scenes) results.push_back(run_scene(s, opt, exec));
  else
    results = run_scenes(scenes, opt);
  if (!lead) return "";
  for (const Scene& s : scenes) std::cerr << "hgrid run: wrote " << result_stem(s, opt) << ".h5 and .csv\n";
  if (!json) return "";
  if (scenes.size() == 1) return results_json(scenes[0], results[0], opt) + "\n";
  std::string out = "[\n";
  for (std::size_t k = 0; k < scenes.size(); ++k)
    out += results_json(scenes[k], results[k], opt) + (k + 1 < scenes.size() ? ",\n" : "\n");
  return out + "]\n";
}

}  // namespace hgrid
