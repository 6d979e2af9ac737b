#include "experiment/runner.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "experiment/detail/results.hpp"
#include "io/atomic_file.hpp"
#include "grid/dispatch.hpp"
#include "model/distribution.hpp"
#include "grid/hgrid.hpp"
#include "model/model.hpp"
#include "packing/packing_model.hpp"
#include "packing/packing_sizes.hpp"
#include "packing/progress.hpp"
#include "experiment/packing_cache.hpp"

namespace hgrid {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// Identifies a point within a scene for the resume journal.
std::string point_key(const ScenePoint& p) { return packing_key(p.packing) + to_string(p.search); }

}  // namespace

PointResult run_point(const Scene& scene, const ScenePoint& point, const RunOptions& opt) {
  PointResult r;
  r.point = point;
  auto t0 = Clock::now();
  const Packing p = cached_packing(point.packing, opt.packing_dir);
  r.seconds_packing = since(t0);
  r.n = p.size();
  r.nu_achieved = p.packing_fraction();

  t0 = Clock::now();
  SizeRequest req;
  req.method = scene.grid.cells;
  req.levels = scene.grid.levels;
  req.q = scene.grid.q;
  const std::vector<double> sizes = model_sizes(p, req, point.search, scene.grid.K);
  r.seconds_sizes = since(t0);

  dispatch(p.d, p.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    constexpr Boundary B = decltype(bnd)::value;
    const auto spheres = p.spheres<D>();
    auto t1 = Clock::now();
    const HGrid<D, B> grid(spheres, p.extent<D>(), GridParams{sizes, point.search});
    r.seconds_build = since(t1);
    t1 = Clock::now();
    r.counts = grid.template for_each_pair<Counted>([](std::uint32_t, std::uint32_t) {});
    r.seconds_query = since(t1);
    r.sizes = grid.sizes();
    if (scene.record.occupancy) {
      const auto occ = grid.occupancy(0);
      r.share_multi_lowest = static_cast<double>(occ[2]) / static_cast<double>(occ[0] + occ[1] + occ[2]);
    } else {
      r.share_multi_lowest = std::nan("");
    }
  });
  const double n = static_cast<double>(r.n);
  r.T_over_N = r.counts.cost(scene.grid.K) / n;
  r.T_cd_over_N = static_cast<double>(r.counts.narrow_phase_checks) / n;
  r.T_ca_over_N = static_cast<double>(r.counts.cell_accesses) / n;
  if (scene.record.model) {
    // The model for the same radii, packing fraction and (fitted) sizes.
    const Empirical dist(p.radii);
    const bool hard_spheres = point.packing.placement == Placement::excluded;
    const PackingModels m =
        model_for_packing(p, sizes_for_grid(r.sizes, 2 * dist.r_max()), point.search, scene.grid.K, hard_spheres);
    r.model_T_over_N = m.random.T_over_N;
    r.model_T_cd_over_N = m.random.T_cd_over_N;
    r.model_T_ca_over_N = m.random.T_ca_over_N;
    const bool excluded = hard_spheres && m.excluded;
    r.model_excluded_T_over_N = excluded ? m.excluded->T_over_N : std::nan("");
    r.model_excluded_T_cd_over_N = excluded ? m.excluded->T_cd_over_N : std::nan("");
    r.model_excluded_T_ca_over_N = excluded ? m.excluded->T_ca_over_N : std::nan("");
  } else {
    r.model_T_over_N = r.model_T_cd_over_N = r.model_T_ca_over_N = std::nan("");
    r.model_excluded_T_over_N = r.model_excluded_T_cd_over_N = r.model_excluded_T_ca_over_N = std::nan("");
  }
  return r;
}

std::string result_stem(const Scene& scene, const RunOptions& opt) {
  const std::string suffix = scene.scale == "default" ? "" : "-" + scene.scale;
  return (std::filesystem::path(opt.results_dir) / (scene.name + suffix)).string();
}

std::vector<PointResult> run_scene(const Scene& scene, const RunOptions& opt) {
  std::filesystem::create_directories(opt.results_dir);
  const std::string stem = result_stem(scene, opt);
  const std::string journal = stem + ".journal.jsonl";
  // Temporary files of runs killed before they could remove them.
  for (const auto& dir : {opt.results_dir, opt.packing_dir}) remove_stale_temporaries(dir, kStaleTemporaryAge);

  // Resume: points measured by an interrupted run of the same scene text.
  std::map<std::string, PointResult> done;
  if (std::ifstream in(journal); in) {
    std::size_t lineno = 0;
    for (std::string line; std::getline(in, line);) {
      ++lineno;
      try {
        const auto j = nlohmann::json::parse(line);
        if (!j.is_object() || !j.contains("source") || j.at("source") != scene.source) continue;
        PointResult r = detail::result_from_json(j.at("result"));
        detail::check_result(r, scene.grid.K);
        done[point_key(r.point)] = r;
      } catch (const std::exception& e) {
        // A line cut short by the interruption, or one changed by hand: that
        // point is measured again.
        if (opt.progress)
          std::cerr << "hgrid run: " << journal << ":" << lineno << " not used (" << e.what()
                    << "); that point is measured again\n";
      }
    }
  }
  std::vector<PointResult> results(scene.points.size());
  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < scene.points.size(); ++i) {
    auto it = done.find(point_key(scene.points[i]));
    if (it != done.end()) {
      results[i] = it->second;
    } else {
      todo.push_back(i);
    }
  }
  if (opt.progress && todo.size() < scene.points.size())
    std::cerr << "hgrid run: " << scene.points.size() - todo.size() << " of " << scene.points.size()
              << " points reused from " << journal << "\n";

  // Points sharing a packing go to one worker, so it is generated once.
  std::vector<std::vector<std::size_t>> groups;
  {
    std::map<std::string, std::size_t> group_of;
    for (std::size_t i : todo) {
      auto [it, fresh] = group_of.emplace(packing_key(scene.points[i].packing), groups.size());
      if (fresh) groups.emplace_back();
      groups[it->second].push_back(i);
    }
  }
  std::mutex mu;
  std::ofstream jout;  // opened with the first result: a run that fails first leaves no journal
  std::atomic<std::size_t> next{0};
  std::size_t finished = 0;
  std::exception_ptr failure;
  Progress progress(opt.progress, "hgrid run " + scene.name, "points");
  auto worker = [&] {
    for (;;) {
      const std::size_t g = next++;
      if (g >= groups.size()) return;
      for (std::size_t i : groups[g]) {
        {
          std::lock_guard<std::mutex> lock(mu);
          if (failure) return;
        }
        try {
          PointResult r = run_point(scene, scene.points[i], opt);
          std::lock_guard<std::mutex> lock(mu);
          results[i] = r;
          if (!jout.is_open()) jout.open(journal, std::ios::app);
          jout << nlohmann::json{{"source", scene.source}, {"result", detail::result_to_json(r)}}.dump() << "\n";
          jout.flush();
          if (!jout) throw InputError("journal", "cannot write '" + journal + "' (disk full?)");
          ++finished;
          progress.count(static_cast<double>(finished), static_cast<double>(todo.size()),
                         std::to_string(finished) + "/" + std::to_string(todo.size()));
        } catch (...) {
          std::lock_guard<std::mutex> lock(mu);
          if (!failure) failure = std::current_exception();
          return;
        }
      }
    }
  };
  const int jobs = std::max(1, std::min<int>(opt.jobs, static_cast<int>(groups.size())));
  std::vector<std::thread> pool;
  for (int t = 1; t < jobs; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  jout.close();
  if (failure) std::rethrow_exception(failure);

  detail::write_results(stem, scene, results);
  std::filesystem::remove(journal);
  return results;
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
