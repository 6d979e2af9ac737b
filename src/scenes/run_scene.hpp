// The one scene runner: what is left of a scene (its journals), its packings
// spread over the processes an executor names, each point measured and
// journalled, the result files written by the lead. The executor is a
// compile-time policy: LocalRun (this process; run_scene(scene, opt)) or
// mpi::RankRun (the ranks of an MPI run, mpi/sweep.hpp). An executor has
//   int rank() const, int size() const        (0 and 1 here)
//   void collective(F f)                      f on every rank; a failure on one fails all
//   std::string broadcast(const std::string&) rank 0's text on every rank
//   std::vector<std::string> gather(const std::string&)  every rank's text on rank 0
#pragma once
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/atomic_file.hpp"
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

}  // namespace hgrid
