#include "hgridlab/scenes/runner.hpp"

#include "hgridlab/scenes/run_scene.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <numeric>
#include <sstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "hgridlab/scenes/detail/results.hpp"
#include "hgridlab/scenes/journal.hpp"
#include "hgridlab/scenes/result_files.hpp"
#include "hgridlab/io/atomic_file.hpp"
#include "hgridlab/base/threads.hpp"
#include "hgridlab/base/clock.hpp"
#include "hgridlab/packing/packing_sizes.hpp"
#include "hgridlab/base/progress.hpp"
#include "hgridlab/io/packing_cache.hpp"

namespace hgrid {

double estimated_work(const PackingSpec& s) {
  const double n = static_cast<double>(s.n);
  if (s.placement != Placement::excluded) return n;
  const double dense = s.nu / 0.35;
  return n * (1 + dense * dense * std::sqrt(std::max(1.0, s.omega)) * (s.equilibrate ? 2 : 1));
}

PointResult run_point(const Scene& scene, const ScenePoint& point, const RunOptions& opt, int threads) {
  PointResult r;
  r.point = point;
  auto t0 = Clock::now();
  // An equilibration shares the cores with the other jobs.
  PackingSpec spec = point.packing;
  spec.threads = threads > 0 ? threads : std::max(1, resolve_threads(0) / std::max(1, opt.jobs));
  const Packing p = cached_packing(spec, opt.packing_dir);
  r.seconds_packing = seconds_since(t0);
  r.equilibration_sweeps = equilibration_sweeps_done(p);

  t0 = Clock::now();
  SizeRequest req;
  req.method = scene.grid.cells;
  req.levels = scene.grid.levels;
  req.q = scene.grid.q;
  const std::vector<double> sizes = model_sizes(p, req, point.search, scene.grid.K);
  r.seconds_sizes = seconds_since(t0);

  MeasureOptions mo;
  mo.K = scene.grid.K;
  mo.model = scene.record.model;
  mo.excluded_model = point.packing.placement == Placement::excluded;  // the hard-sphere model for hard spheres
  mo.occupancy = scene.record.occupancy;
  r.m = measure(p, GridParams{sizes, point.search}, mo);
  return r;
}

std::string result_stem(const Scene& scene, const RunOptions& opt) {
  const std::string suffix = scene.scale == "default" ? "" : "-" + scene.scale;
  return (std::filesystem::path(opt.results_dir) / (scene.name + suffix)).string();
}

std::vector<std::vector<std::size_t>> group_by_packing(const Scene& scene, const std::vector<std::size_t>& todo) {
  std::vector<std::vector<std::size_t>> groups;
  std::map<std::string, std::size_t> group_of;
  for (std::size_t i : todo) {
    auto [it, fresh] = group_of.emplace(packing_key(scene.points[i].packing), groups.size());
    if (fresh) groups.emplace_back();
    groups[it->second].push_back(i);
  }
  return groups;
}

namespace {

/// A point of a pooled run: which scene, which of its points.
struct PooledPoint {
  std::size_t scene, point;
};

/// One scene's place in a pooled run: where its points' results and
/// journal lines go.
struct SceneSlot {
  const Scene* scene;
  std::string journal;
  std::vector<PointResult>* results;
};

/// measure_groups() over the groups of several scenes (a group: the points,
/// of any of the scenes, of one packing).
std::optional<PointFailure> measure_pooled(const std::vector<SceneSlot>& slots,
                                           const std::vector<std::vector<PooledPoint>>& groups,
                                           const RunOptions& opt, const std::string& what) {
  std::size_t total = 0;
  for (const auto& g : groups) total += g.size();
  const auto spec_of = [&](const PooledPoint& q) -> const PackingSpec& {
    return slots[q.scene].scene->points[q.point].packing;
  };
  // The largest first (stable: ties in scene order).
  std::vector<std::size_t> order(groups.size());
  for (std::size_t g = 0; g < order.size(); ++g) order[g] = g;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return estimated_work(spec_of(groups[a].front())) > estimated_work(spec_of(groups[b].front()));
  });
  const int jobs = std::max(1, std::min<int>(opt.jobs, static_cast<int>(groups.size())));
  std::atomic<int> running{jobs};  // jobs not yet out of groups: the cores are theirs
  std::mutex mu;
  std::vector<JournalWriter> journals;
  journals.reserve(slots.size());
  for (const SceneSlot& s : slots) journals.emplace_back(s.journal, s.scene->source);
  std::atomic<std::size_t> next{0};
  std::size_t finished = 0;
  std::optional<PointFailure> failure;
  Progress progress(opt.progress, what, "points");
  auto worker = [&] {
    for (;;) {
      const std::size_t at = next++;
      if (at >= groups.size()) {
        --running;
        return;
      }
      for (const PooledPoint& q : groups[order[at]]) {
        {
          std::lock_guard<std::mutex> lock(mu);
          if (failure) return;
        }
        const SceneSlot& slot = slots[q.scene];
        try {
          const int threads = std::max(1, resolve_threads(0) / std::max(1, running.load()));
          PointResult r = run_point(*slot.scene, slot.scene->points[q.point], opt, threads);
          std::lock_guard<std::mutex> lock(mu);
          (*slot.results)[q.point] = r;
          journals[q.scene].append(r);
          ++finished;
          progress.count(static_cast<double>(finished), static_cast<double>(total),
                         std::to_string(finished) + "/" + std::to_string(total));
        } catch (...) {
          std::lock_guard<std::mutex> lock(mu);
          if (!failure) failure = PointFailure{q.point, std::current_exception(), q.scene};
          return;
        }
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < jobs; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  return failure;
}

}  // namespace

std::optional<PointFailure> measure_groups(const Scene& scene, const std::vector<std::vector<std::size_t>>& groups,
                                           const RunOptions& opt, const std::string& journal, const std::string& what,
                                           std::vector<PointResult>& results) {
  std::vector<std::vector<PooledPoint>> pooled(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (std::size_t i : groups[g]) pooled[g].push_back({0, i});
  return measure_pooled({SceneSlot{&scene, journal, &results}}, pooled, opt, what);
}

std::vector<std::vector<PointResult>> run_scenes(const std::vector<Scene>& scenes, const RunOptions& opt) {
  if (scenes.size() == 1) return {run_scene(scenes[0], opt)};
  std::vector<std::string> stems;
  for (const Scene& s : scenes) {
    stems.push_back(result_stem(s, opt));
    if (std::count(stems.begin(), stems.end(), stems.back()) > 1)
      throw InputError("SCENE", "two scenes would write the same result files (" + stems.back() + ".h5)");
  }
  std::filesystem::create_directories(opt.results_dir);
  for (const auto& dir : {opt.results_dir, opt.packing_dir}) remove_stale_temporaries(dir, kStaleTemporaryAge);
  std::vector<Resumed> resumed;
  for (std::size_t k = 0; k < scenes.size(); ++k) resumed.push_back(resume(scenes[k], stems[k], opt.progress));
  // One group per packing, across the scenes.
  std::vector<std::vector<PooledPoint>> groups;
  std::map<std::string, std::size_t> group_of;
  for (std::size_t k = 0; k < scenes.size(); ++k)
    for (std::size_t i : resumed[k].todo) {
      auto [it, fresh] = group_of.emplace(packing_key(scenes[k].points[i].packing), groups.size());
      if (fresh) groups.emplace_back();
      groups[it->second].push_back({k, i});
    }
  std::vector<std::vector<PointResult>> measured(scenes.size());
  std::vector<SceneSlot> slots;
  std::string what = "hgrid run";
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    measured[k].resize(scenes[k].points.size());
    slots.push_back({&scenes[k], journal_path(stems[k], 0), &measured[k]});
    what += (k ? "+" : " ") + scenes[k].name;
  }
  if (const auto failure = measure_pooled(slots, groups, opt, what))
    detail::rethrow_naming_point(scenes[failure->scene], *failure);
  std::vector<std::vector<PointResult>> out;
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    for (std::size_t i : resumed[k].todo) resumed[k].results[i] = measured[k][i];
    write_results(stems[k], scenes[k], resumed[k].results);
    remove_journals(stems[k]);
    out.push_back(std::move(resumed[k].results));
  }
  return out;
}

std::vector<PointResult> run_scene(const Scene& scene, const RunOptions& opt) {
  LocalRun here;
  return run_scene(scene, opt, here);
}

std::vector<int> assign_groups(const Scene& scene, const std::vector<std::vector<std::size_t>>& groups, int processes) {
  std::vector<double> work(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g)
    work[g] =
        static_cast<double>(scene.points.at(groups[g].front()).packing.n) * static_cast<double>(groups[g].size() + 1);
  std::vector<std::size_t> order(groups.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return work[a] > work[b]; });
  std::vector<double> load(static_cast<std::size_t>(std::max(processes, 1)), 0.0);
  std::vector<int> owner(groups.size());
  for (std::size_t g : order) {
    const auto least = std::min_element(load.begin(), load.end());  // the first of equals
    *least += work[g];
    owner[g] = static_cast<int>(least - load.begin());
  }
  return owner;
}

void detail::rethrow_naming_point(const Scene& scene, const PointFailure& f) {
  const std::string where = " [at " + describe_point(scene, f.point) + "]";
  try {
    std::rethrow_exception(f.error);
  } catch (const InputError& e) {
    throw InputError(e.field(), e.problem() + where);
  } catch (const std::exception& e) {
    throw std::runtime_error(e.what() + where);
  }
}

std::string detail::indices_text(const std::vector<std::size_t>& v) {
  std::string out;
  for (std::size_t i : v) out += std::to_string(i) + ' ';
  return out;
}

std::vector<std::size_t> detail::indices_from_text(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::size_t> out;
  for (std::size_t i; in >> i;) out.push_back(i);
  return out;
}

std::string results_json(const Scene& scene, const std::vector<PointResult>& results, const RunOptions& opt) {
  nlohmann::json out;
  out["scene"] = scene.name;
  out["scale"] = scene.scale;
  out["results"] = result_stem(scene, opt) + ".h5";
  out["points"] = nlohmann::json::array();
  for (const auto& r : results) out["points"].push_back(detail::result_to_json(r));
  return out.dump(2);
}

}  // namespace hgrid
