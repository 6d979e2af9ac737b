#include "hgridlab/scenes/runner.hpp"

#include "hgridlab/scenes/run_scene.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
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
#include "hgridlab/packing/packing_sizes.hpp"
#include "hgridlab/base/progress.hpp"
#include "hgridlab/io/packing_cache.hpp"

namespace hgrid {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

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
  r.seconds_packing = since(t0);
  r.equilibration_sweeps = equilibration_sweeps_done(p);

  t0 = Clock::now();
  SizeRequest req;
  req.method = scene.grid.cells;
  req.levels = scene.grid.levels;
  req.q = scene.grid.q;
  const std::vector<double> sizes = model_sizes(p, req, point.search, scene.grid.K);
  r.seconds_sizes = since(t0);

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

std::optional<PointFailure> measure_groups(const Scene& scene, const std::vector<std::vector<std::size_t>>& groups,
                                           const RunOptions& opt, const std::string& journal, const std::string& what,
                                           std::vector<PointResult>& results) {
  std::size_t total = 0;
  for (const auto& g : groups) total += g.size();
  // The largest first (stable: ties in scene order).
  std::vector<std::size_t> order(groups.size());
  for (std::size_t g = 0; g < order.size(); ++g) order[g] = g;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return estimated_work(scene.points[groups[a].front()].packing) >
           estimated_work(scene.points[groups[b].front()].packing);
  });
  const int jobs = std::max(1, std::min<int>(opt.jobs, static_cast<int>(groups.size())));
  std::atomic<int> running{jobs};  // jobs not yet out of groups: the cores are theirs
  std::mutex mu;
  JournalWriter jout(journal, scene.source);
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
      const std::size_t g = order[at];
      for (std::size_t i : groups[g]) {
        {
          std::lock_guard<std::mutex> lock(mu);
          if (failure) return;
        }
        try {
          const int threads = std::max(1, resolve_threads(0) / std::max(1, running.load()));
          PointResult r = run_point(scene, scene.points[i], opt, threads);
          std::lock_guard<std::mutex> lock(mu);
          results[i] = r;
          jout.append(r);
          ++finished;
          progress.count(static_cast<double>(finished), static_cast<double>(total),
                         std::to_string(finished) + "/" + std::to_string(total));
        } catch (...) {
          std::lock_guard<std::mutex> lock(mu);
          if (!failure) failure = PointFailure{i, std::current_exception()};
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
