#include "hgridlab/mpi/sweep.hpp"

#include <algorithm>
#include <filesystem>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "hgridlab/scenes/journal.hpp"
#include "hgridlab/scenes/result_files.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/io/atomic_file.hpp"
#include "hgridlab/mpi/comm.hpp"

namespace hgrid::mpi {
namespace {

/// A failed point as the message every rank's user reads: the error, and
/// which point of the scene it was. An InputError stays one (exit status 2).
[[noreturn]] void rethrow_naming_point(const Scene& scene, const PointFailure& f) {
  const std::string where = " [at " + describe_point(scene, f.point) + "]";
  try {
    std::rethrow_exception(f.error);
  } catch (const InputError& e) {
    throw InputError(e.field(), e.problem() + where);
  } catch (const std::exception& e) {
    throw std::runtime_error(e.what() + where);
  }
}

std::string to_text(const std::vector<std::size_t>& v) {
  std::string out;
  for (std::size_t i : v) out += std::to_string(i) + ' ';
  return out;
}

std::vector<std::size_t> from_text(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::size_t> out;
  for (std::size_t i; in >> i;) out.push_back(i);
  return out;
}

}  // namespace

std::vector<int> assign_groups(const Scene& scene, const std::vector<std::vector<std::size_t>>& groups, int ranks) {
  std::vector<double> work(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g)
    work[g] =
        static_cast<double>(scene.points.at(groups[g].front()).packing.n) * static_cast<double>(groups[g].size() + 1);
  std::vector<std::size_t> order(groups.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return work[a] > work[b]; });
  std::vector<double> load(static_cast<std::size_t>(std::max(ranks, 1)), 0.0);
  std::vector<int> owner(groups.size());
  for (std::size_t g : order) {
    const auto least = std::min_element(load.begin(), load.end());  // the first of equals
    *least += work[g];
    owner[g] = static_cast<int>(least - load.begin());
  }
  return owner;
}

std::vector<PointResult> run_scene_on_ranks(const Scene& scene, const RunOptions& opt) {
  if (size() == 1) return run_scene(scene, opt);
  const bool lead = rank() == 0;
  const std::string stem = result_stem(scene, opt);
  Resumed resumed;
  collective([&] {
    // Every rank must sweep the same points: a scene file edited while the
    // ranks were starting would mix two scenes.
    if (broadcast(scene.source) != scene.source)
      throw InputError("SCENE", "the scene file differs from rank 0's (changed while the run started?)");
    std::filesystem::create_directories(opt.results_dir);
    for (const auto& dir : {opt.results_dir, opt.packing_dir}) remove_stale_temporaries(dir, kStaleTemporaryAge);
    // Rank 0 alone decides what is left: ranks reading the journals
    // themselves could see different files (a shared file system that shows
    // a new file late) and then measure a point twice or never.
    if (lead) resumed = resume(scene, stem, opt.progress);
  });
  const std::vector<std::size_t> todo = from_text(broadcast(lead ? to_text(resumed.todo) : std::string()));
  const auto groups = group_by_packing(scene, todo);
  const std::vector<int> owner = assign_groups(scene, groups, size());
  std::vector<std::vector<std::size_t>> mine;
  for (std::size_t g = 0; g < groups.size(); ++g)
    if (owner[g] == rank()) mine.push_back(groups[g]);

  // The generators' own progress lines from rank 0 only; every rank counts
  // its points on a line of its own.
  Scene local = scene;
  if (!lead)
    for (auto& p : local.points) p.packing.progress = false;
  std::vector<PointResult> measured(scene.points.size());
  collective([&] {
    const std::string what =
        "hgrid run " + scene.name + " [rank " + std::to_string(rank()) + "/" + std::to_string(size()) + "]";
    if (const auto failure = measure_groups(local, mine, opt, journal_path(stem, rank()), what, measured))
      rethrow_naming_point(scene, *failure);
  });

  // One line per point: "<index> <result as JSON>".
  std::string sent;
  for (const auto& g : mine)
    for (std::size_t i : g) sent += std::to_string(i) + ' ' + result_json_line(measured[i]) + '\n';
  const std::vector<std::string> received = gather(sent);
  collective([&] {
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
      throw std::logic_error("run_scene_on_ranks: " + std::to_string(count) + " results gathered for " +
                             std::to_string(todo.size()) + " points");
    write_results(stem, scene, resumed.results);
    remove_journals(stem);
  });
  return lead ? resumed.results : std::vector<PointResult>{};
}

}  // namespace hgrid::mpi
