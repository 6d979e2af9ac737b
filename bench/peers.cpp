// hgridlab against its peers: the HGrid vs the single-level linked
// cell, CGAL box_intersection_d, Embree's BVH self-collision (rtcCollide),
// Bullet's dynamic AABB tree broadphase (btDbvtBroadphase) and LAMMPS
// `neighbor multi` / `bin`, and MercuryDPM's HGrid (bench/mercurydpm/peer.cpp,
// given a MercuryDPM build), on the figure-11 packing (3D, periodic,
// alpha = -3, omega = 100, nu = 0.6, excluded volume). Every tool must find
// the same number of pairs (distance < r_i + r_j); a disagreement exits with
// status 1. --threads N gives hgridlab and Embree N threads and runs LAMMPS
// on N MPI ranks (mpirun -np N); Bullet's broadphase has one thread.
// hgridlab is also sampled on one thread then (speedup_threads).
//
//   build/peers --n 100000 --json          (see --help; LAMMPS: `lmp` on PATH)
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <unistd.h>
#include <memory>
#include <iostream>
#include <nlohmann/json.hpp>

#include "bench/detail/bullet_pairs.hpp"
#include "bench/detail/cgal_pairs.hpp"
#include "bench/detail/embree_pairs.hpp"
#include "bench/detail/periodic_images.hpp"
#include "hgridlab/grid/dispatch.hpp"
#include "hgridlab/packing/generate.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/io/lammps_export.hpp"
#include "hgridlab/io/peer_settings.hpp"
#include "hgridlab/calibration/k_choice.hpp"
#include "hgridlab/advice/recommend.hpp"
#include "bench/lammps_run.hpp"
#include "hgridlab/packing/packing_sizes.hpp"
#include "hgridlab/io/provenance.hpp"
#include "hgridlab/io/packing_cache.hpp"
#include "hgridlab/io/viewer_files.hpp"
#include "hgridlab/packing/grid_placement.hpp"

namespace {

using namespace hgrid;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

struct Options {
  PackingSpec spec;
  std::string placement = "excluded", boundary = "periodic", cache = "results/packings", work, csv, scan = "auto";
  std::string mercurydpm;  // the mercurydpm_peer driver (bench/mercurydpm); empty: $MERCURYDPM_BUILD's, if built
  int repeats = 3, builds = 5, bin_builds = 1, lammps_reruns = 2, threads = 1;
  bool as_json = false, no_cgal = false, no_embree = false, no_bullet = false, no_lammps = false, no_bin = false, linked_cell = false, no_linked_cell = false;
};

/// Best wall time of `repeats` calls of f (which returns the pair count).
template <class F>
std::pair<double, std::uint64_t> best_of(int repeats, F&& f) {
  double best = 1e300;
  std::uint64_t pairs = 0;
  for (int k = 0; k < repeats; ++k) {
    const auto t0 = Clock::now();
    pairs = f();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
  }
  return {best, pairs};
}

/// Best time of `repeats` timed runs of f (which returns a bench::PeerRun,
/// timing itself), and the pair count of the last.
template <class F>
std::pair<double, std::uint64_t> best_timed(int repeats, F&& f) {
  double best = 1e300;
  std::uint64_t pairs = 0;
  for (int k = 0; k < repeats; ++k) {
    const bench::PeerRun r = f();
    best = std::min(best, r.seconds), pairs = r.pairs;
  }
  return {best, pairs};
}

/// The 1-minute load average (Linux), or -1: timings under load are not
/// comparable with idle ones, so every run records it.
double load_average() {
  std::FILE* f = std::fopen("/proc/loadavg", "r");
  double la = -1;
  if (f) {
    if (std::fscanf(f, "%lf", &la) != 1) la = -1;
    std::fclose(f);
  }
  return la;
}

json tool(double seconds, std::uint64_t pairs, double n) {
  return json{{"seconds_per_build", seconds}, {"seconds_per_particle", seconds / n}, {"pairs", pairs}};
}

/// Size-class candidates for LAMMPS multi: k geometric classes from `smallest`
/// (a multiple of the smallest diameter). Candidates whose smallest class
/// would need more than kMaxBins bins (LAMMPS bins it at half its cutoff; at
/// N = 1e6 the smallest diameter gives "Too many neighbor bins", and 1e8 bins
/// take a minute to set up) are left out: the scan keeps the coarser ones.
constexpr double kMaxBins = 3e7;
std::vector<std::pair<int, double>> scan_candidates(const std::string& scan, const Packing& p, double dmin) {
  std::vector<std::pair<int, double>> c;
  const bool full = scan == "full" || (scan == "auto" && p.size() <= 200000);
  const std::vector<int> ks = full ? std::vector<int>{2, 3, 4, 6} : std::vector<int>{3, 4};
  for (double f : {1.0, 2.0, 4.0, 8.0, 16.0, 32.0}) {
    double bins = 1;
    for (int a = 0; a < p.d; ++a) bins *= p.box[a] / (0.5 * f * dmin) + 4;
    if (bins > kMaxBins) continue;
    for (int k : ks) c.push_back({k, f * dmin});
    if (!full && c.size() >= 6) break;
  }
  return c;
}

json run_lammps_tools(const Options& o, const Packing& p, const std::string& lmp, std::uint64_t& multi_pairs,
                      std::uint64_t& bin_pairs, double& multi_s, double& bin_s, const std::function<void()>& after_run) {
  json out;
  const std::string dir = o.work;
  const double dmin = 2 * *std::min_element(p.radii.begin(), p.radii.end());
  json scan = json::array();
  double best = 1e300;
  LammpsScript s;
  s.builds = o.builds;
  std::vector<double> best_c;
  std::vector<std::uint64_t> pair_counts;
  // One run per class set; then the two fastest sets run again, as hgridlab
  // is sampled again between the runs: LAMMPS multi's time for the same set
  // varies by up to a third between runs on an otherwise quiet machine
  // (docs/record/PERFORMANCE.md, run 12), and a single run would let that fall on
  // LAMMPS alone.
  auto attempt = [&](const std::vector<double>& collections, json& row) {
    s.collections = collections;
    export_lammps(dir, p, s);
    const LammpsResult r = run_lammps(lmp, dir, "in.multi.lmp", o.threads);
    after_run();
    row["collections"] = collections;
    row["ok"] = r.ok;
    if (!r.ok) {
      row["error"] = r.error;
      return 1e300;
    }
    row["seconds_per_build"] = r.max_seconds_per_build();
    if (o.threads > 1) row["avg_seconds_per_build"] = r.seconds_per_build();
    row["comm_seconds_per_build"] = r.comm_seconds / static_cast<double>(std::max<std::uint64_t>(r.builds, 1));
    row["pairs"] = r.pairs;
    if (!pair_counts.empty() && r.pairs != pair_counts.front())
      out["lammps_multi_pairs_error"] = "runs found different pair counts";
    pair_counts.push_back(r.pairs);
    if (r.max_seconds_per_build() < best) best = r.max_seconds_per_build(), best_c = collections, multi_pairs = r.pairs;
    return r.max_seconds_per_build();
  };
  std::vector<std::pair<double, std::vector<double>>> ranked;
  for (auto [k, smallest] : scan_candidates(o.scan, p, dmin)) {
    json row;
    const auto c = geometric_collections(p, k, smallest);
    ranked.push_back({attempt(c, row), c});
    std::cerr << "peers: lammps multi " << row.dump() << "\n";
    scan.push_back(row);
  }
  std::sort(ranked.begin(), ranked.end());
  json reruns = json::array();
  for (std::size_t m = 0; m < std::min<std::size_t>(2, ranked.size()); ++m) {
    if (ranked[m].first >= 1e300) break;
    for (int r = 0; r < o.lammps_reruns; ++r) {
      json row;
      attempt(ranked[m].second, row);
      std::cerr << "peers: lammps multi again " << row.dump() << "\n";
      reruns.push_back(row);
    }
  }
  if (best < 1e300) {
    multi_s = best;
    out["lammps_multi_collections"] = best_c;
  }
  out["lammps_multi_scan"] = scan;
  out["lammps_multi_reruns"] = reruns;
  const double best_scanned = best;
  const std::vector<double> scanned_c = best_c;
  // The collections `hgrid recommend` gives (LAMMPS's own cost model; same
  // script otherwise), run as often as the fastest scanned sets: its best
  // over the best scanned set's.
  std::string model_source;
  const std::vector<double> rc =
      rounded_up_sizes(lammps_collections_for(p.radii, p.d, p.packing_fraction(), &model_source));
  json rec_runs = json::array();
  double rec_best = 1e300;
  for (int r = 0; r <= o.lammps_reruns; ++r) {
    json row;
    rec_best = std::min(rec_best, attempt(rc, row));
    std::cerr << "peers: lammps multi recommended " << row.dump() << "\n";
    rec_runs.push_back(row);
  }
  out["lammps_recommended_collections"] = rc;
  out["lammps_recommended_model"] = model_source;
  out["lammps_recommended_runs"] = rec_runs;
  if (rec_best < 1e300 && best_scanned < 1e300) {
    out["lammps_recommended_seconds_per_build"] = rec_best;
    out["ratio_lammps_recommended_vs_best"] = rec_best / best_scanned;
  }
  // LAMMPS multi's time against hgridlab: its fastest set, scanned or
  // recommended (`attempt` kept the best of all runs).
  if (best < 1e300) {
    multi_s = best;
    out["lammps_multi_collections"] = best_c;
    out["lammps_multi_from"] = best < best_scanned ? "recommended" : "scan";
  }
  best_c = scanned_c;
  if (!o.no_bin) {
    s.builds = o.bin_builds;
    s.collections = best_c.empty() ? geometric_collections(p, 1, dmin) : best_c;
    export_lammps(dir, p, s);
    const LammpsResult r = run_lammps(lmp, dir, "in.bin.lmp", o.threads);
    after_run();
    if (r.ok) {
      bin_s = r.max_seconds_per_build(), bin_pairs = r.pairs;
    } else {
      out["lammps_bin_error"] = r.error;
    }
  }
  return out;
}

/// The driver of MercuryDPM's HGrid (bench/mercurydpm/peer.cpp): --mercurydpm,
/// else $MERCURYDPM_BUILD/drivers/mercurydpm_peer when it exists; "" otherwise.
std::string mercurydpm_driver(const Options& o) {
  if (!o.mercurydpm.empty()) return o.mercurydpm;
  const char* b = std::getenv("MERCURYDPM_BUILD");
  if (!b || !*b) return "";
  const std::string path = std::string(b) + "/drivers/mercurydpm_peer";
  return std::filesystem::exists(path) ? path : "";
}

/// One run of the driver on FILE.xyz: its JSON (one object on stdout).
json run_mercurydpm(const std::string& driver, const std::string& xyz, int d, const std::string& sizes,
                    const std::string& boundary, int repeats) {
  const std::string cmd = "'" + driver + "' '" + xyz + "' " + std::to_string(d) + " " + sizes + " " + boundary + " " +
                          std::to_string(repeats);
  std::FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + driver);
  std::string out;
  char buf[4096];
  for (std::size_t k; (k = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, k);
  const int rc = ::pclose(pipe);
  if (rc != 0) throw std::runtime_error(driver + " failed (" + cmd + ")");
  return json::parse(out);
}

int run(Options o) {
  o.spec.placement = parse_placement(o.placement);
  o.spec.boundary = parse_boundary(o.boundary);
  if (o.spec.n == 0) throw InputError("n", "must be > 0");
  if (o.builds < 1) throw InputError("builds", "must be >= 1");
  if (o.repeats < 1) throw InputError("repeats", "must be >= 1");
  if (o.bin_builds < 1) throw InputError("bin-builds", "must be >= 1");
  if (o.lammps_reruns < 0) throw InputError("lammps-reruns", "must be >= 0");
  if (o.threads < 1) throw InputError("threads", "must be >= 1");
  const Packing p = cached_packing(o.spec, o.cache);
  const double n = static_cast<double>(p.size());
  json j{{"n", p.size()}, {"d", p.d}, {"nu", o.spec.nu}, {"alpha", o.spec.alpha}, {"omega", o.spec.omega},
         {"placement", o.placement}, {"boundary", o.boundary}, {"seed", o.spec.seed}, {"commit", git_hash()},
         {"load_average_at_start", load_average()}, {"threads", o.threads}, {"hgrid_threads", o.threads},
         {"packing", packing_cache_path(o.spec, o.cache)}};
  std::map<std::string, std::uint64_t> pairs;
  std::map<std::string, double> secs;
  // hgridlab's time: the best of its samples (see below), each the mean of
  // o.builds consecutive builds. LAMMPS multi's is the best of its class
  // sets, whose runs spread over minutes; sampling hgridlab before, between
  // and after the other tools' runs spreads it over the same minutes, so that
  // a slow phase of the machine weighs on both tools alike.
  // With --threads N > 1, hgridlab runs on N threads, and a sample on one
  // thread is taken beside each (speedup_threads: same run, same moments).
  std::function<std::pair<double, std::uint64_t>(int)> sample_hgrid;  // argument: threads
  std::vector<double> samples, samples_one;
  bool samples_agree = true;
  const auto take_sample = [&] {
    const auto [sec, c] = sample_hgrid(o.threads);
    if (samples.empty()) pairs["hgrid"] = c;
    samples_agree = samples_agree && c == pairs["hgrid"];
    samples.push_back(sec);
    if (o.threads > 1) {
      const auto [sec1, c1] = sample_hgrid(1);
      samples_agree = samples_agree && c1 == pairs["hgrid"];
      samples_one.push_back(sec1);
    }
  };
  const std::vector<double> sizes = model_sizes(p, SizeRequest{}, Search::top_down, 0.2);  // optimal
  const double rmax = *std::max_element(p.radii.begin(), p.radii.end());
  const bool linked = o.linked_cell || (!o.no_linked_cell && p.size() <= 200000);
  dispatch(p.d, p.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    constexpr Boundary B = decltype(bnd)::value;
    const auto s = p.spheres<D>();
    const auto box = p.extent<D>();
    auto grid_run = [&](const std::vector<double>& sz) {
      const HGrid<D, B> g(s, box, GridParams{sz, Search::top_down});
      std::uint64_t c = 0;
      g.template query<Search::top_down, Uncounted>([&c](std::uint32_t, std::uint32_t) { ++c; });
      return c;
    };
    // As LAMMPS keeps its bins and lists between the builds it times, one
    // grid, constructed before the timing, is rebuilt per build (the way a
    // time-stepping code uses it); a new grid per build is recorded too.
    // A sample is the mean of o.builds consecutive builds after one untimed
    // build, as LAMMPS's time of one run is the mean of the builds of its
    // run loop after the untimed build of its setup (after minutes of
    // waiting for another tool, the first build here is ~20 % slower than
    // the next ones); samples are taken now and after every other tool's run.
    auto kept = std::make_shared<HGrid<D, B>>(s, box, GridParams{sizes, Search::top_down, o.threads});
    auto kept_one = o.threads > 1 ? std::make_shared<HGrid<D, B>>(s, box, GridParams{sizes, Search::top_down, 1}) : kept;
    auto spheres = std::make_shared<std::vector<Sphere<D>>>(s);
    sample_hgrid = [kept, kept_one, spheres, &o](int threads) {
      const auto& grid = threads > 1 ? kept : kept_one;
      struct alignas(64) Slot {  // pairs counted per thread (base/threads.hpp)
        std::uint64_t n = 0;
      };
      std::vector<Slot> found(static_cast<std::size_t>(threads));
      std::uint64_t c = 0;
      auto build = [&] {
        grid->rebuild(*spheres);
        for (auto& f : found) f.n = 0;
        grid->template query<Search::top_down, Uncounted>(
            [&found](int t, std::uint32_t, std::uint32_t) { ++found[static_cast<std::size_t>(t)].n; });
        c = 0;
        for (const auto& f : found) c += f.n;
      };
      build();  // untimed, as LAMMPS's setup
      const auto t0 = Clock::now();
      for (int k = 0; k < o.builds; ++k) build();
      return std::pair{std::chrono::duration<double>(Clock::now() - t0).count() / o.builds, c};
    };
    take_sample();
    const auto [new_s, new_pairs] = best_of(o.repeats, [&] { return grid_run(sizes); });
    j["hgrid_new_grid"] = tool(new_s, new_pairs, n);
    if (new_pairs != pairs["hgrid"]) j["hgrid_new_grid_error"] = "a new grid found another pair count";
    j["hgrid_sizes"] = sizes;
    if (linked) std::tie(secs["linked_cell"], pairs["linked_cell"]) = best_of(1, [&] { return grid_run({2 * rmax}); });
#ifdef HGRID_HAVE_CGAL
    if (!o.no_cgal) {
      std::tie(secs["cgal"], pairs["cgal"]) =
          best_of(o.repeats, [&] { return bench::cgal_pairs<D, B>(std::span<const Sphere<D>>(s), box); });
      take_sample();
    }
#else
    j["cgal_skipped"] = "built without CGAL";
#endif
#ifdef HGRID_HAVE_EMBREE
    if (!o.no_embree) {
      try {
        bench::EmbreeCollider embree(o.threads);
        j["embree_threads"] = embree.threads();
        j["embree_tasking"] = embree.tasking();
        j["embree_version"] = RTC_VERSION_STRING;
        j["embree_build_quality"] = "low";
        std::tie(secs["embree"], pairs["embree"]) = best_timed(
            o.repeats, [&] { return embree.template pairs<D, B>(std::span<const Sphere<D>>(s), box); });
      } catch (const std::exception& e) {
        j["embree_error"] = e.what();
      }
      take_sample();
    }
#else
    j["embree_skipped"] = "built without Embree";
#endif
#ifdef HGRID_HAVE_BULLET
    if (!o.no_bullet) {
      j["bullet_threads"] = 1;
      j["bullet_precision"] = bench::bullet_precision();
      j["bullet_deferred_collide"] = true;
      std::tie(secs["bullet"], pairs["bullet"]) =
          best_timed(o.repeats, [&] { return bench::bullet_pairs<D, B>(std::span<const Sphere<D>>(s), box); });
      take_sample();
    }
#else
    j["bullet_skipped"] = "built without Bullet";
#endif
  });
  if (!linked) j["linked_cell_skipped"] = "N > 2e5 (minutes per build); --linked-cell forces it";
  for (const char* t : {"cgal", "embree", "bullet"})
    if (j.contains(std::string(t) + "_skipped"))
      std::cerr << "peers: " << t << " skipped: " << j[std::string(t) + "_skipped"].get<std::string>() << "\n";
  if (j.contains("embree_error")) std::cerr << "peers: error: Embree: " << j["embree_error"].get<std::string>() << "\n";
  const auto lmp = o.no_lammps ? std::nullopt : find_lammps();
  if (lmp) {
    if (o.work.empty()) o.work = "results/peers/lammps-n" + std::to_string(p.size());
    double ms = 0, bs = 0;
    std::uint64_t mp = 0, bp = 0;
    j["lammps_ranks"] = o.threads;
    j.update(run_lammps_tools(o, p, *lmp, mp, bp, ms, bs, take_sample));
    if (ms > 0) secs["lammps_multi"] = ms, pairs["lammps_multi"] = mp;
    if (bs > 0) secs["lammps_bin"] = bs, pairs["lammps_bin"] = bp;
  } else {
    j["lammps_skipped"] = o.no_lammps ? "--no-lammps" : "lmp not on PATH (apt-get install lammps)";
    std::cerr << "peers: LAMMPS skipped: " << j["lammps_skipped"].get<std::string>() << "\n";
  }
  // MercuryDPM's HGrid (the paper's authors' code): with hgridlab's sizes
  // and with its own default, on the packing's boundary (periodic: its
  // ghosts, as its simulations make them every step); and the same centres
  // in an open box (no ghosts) beside hgridlab's grid of that box.
  std::map<std::string, std::pair<double, std::uint64_t>> open_box;  // name -> (seconds, pairs)
  if (const std::string driver = mercurydpm_driver(o); !driver.empty()) {
    // The packing for the driver: a temporary extended XYZ file, removed after.
    const std::string xyz = (std::filesystem::temp_directory_path() /
                             ("hgridlab-peers-mercurydpm-" + std::to_string(::getpid()) + ".xyz")).string();
    write_extended_xyz(xyz, p, place_in_grid(p, GridParams{sizes, Search::top_down}));
    struct Remove {
      std::string path;
      ~Remove() { std::filesystem::remove(path); }
    } remove{xyz};
    std::string given;
    for (double v : sizes) given += (given.empty() ? "" : ",") + format_number(v);
    const std::string own = p.boundary == Boundary::periodic ? "periodic" : "open";
    try {
      const json a = run_mercurydpm(driver, xyz, p.d, given, own, o.repeats);
      take_sample();
      const json b = run_mercurydpm(driver, xyz, p.d, "default", own, o.repeats);
      take_sample();
      j["mercurydpm_given_sizes_run"] = a;
      j["mercurydpm_default_run"] = b;
      secs["mercurydpm"] = a["seconds_per_build"], pairs["mercurydpm"] = a["pairs"];
      secs["mercurydpm_default"] = b["seconds_per_build"], pairs["mercurydpm_default"] = b["pairs"];
      if (own == "periodic") {
        const json c = run_mercurydpm(driver, xyz, p.d, given, "open", o.repeats);
        j["mercurydpm_open_box_run"] = c;
        open_box["mercurydpm"] = {c["seconds_per_build"], c["pairs"]};
        Packing q = p;
        q.boundary = Boundary::walls;
        dispatch(q.d, Boundary::walls, [&](auto dim, auto) {
          constexpr int D = decltype(dim)::value;
          const auto sp = q.spheres<D>();
          HGrid<D, Boundary::walls> g(sp, q.extent<D>(), GridParams{sizes, Search::top_down});
          open_box["hgrid"] = best_of(o.repeats, [&] {
            g.rebuild(sp);
            std::uint64_t k = 0;
            g.template query<Search::top_down, Uncounted>([&k](std::uint32_t, std::uint32_t) { ++k; });
            return k;
          });
        });
        j["hgrid_open_box"] = tool(open_box["hgrid"].first, open_box["hgrid"].second, n);
        j["ratio_open_box_vs_mercurydpm"] = open_box["mercurydpm"].first / open_box["hgrid"].first;
        take_sample();
      }
      j["mercurydpm_driver"] = driver;
    } catch (const std::exception& e) {
      j["mercurydpm_error"] = e.what();
      std::cerr << "peers: error: MercuryDPM: " << e.what() << "\n";
    }
  } else {
    j["mercurydpm_skipped"] = "no MercuryDPM build (bench/mercurydpm/build.sh, then MERCURYDPM_BUILD or --mercurydpm)";
    std::cerr << "peers: MercuryDPM skipped: " << j["mercurydpm_skipped"].get<std::string>() << "\n";
  }
  take_sample();
  secs["hgrid"] = *std::min_element(samples.begin(), samples.end());
  j["hgrid_samples_seconds_per_build"] = samples;
  if (!samples_one.empty()) {
    const double one = *std::min_element(samples_one.begin(), samples_one.end());
    j["hgrid_one_thread"] = tool(one, pairs["hgrid"], n);
    j["hgrid_one_thread_samples_seconds_per_build"] = samples_one;
    j["speedup_threads"] = one / secs["hgrid"];
  } else {
    j["speedup_threads"] = 1.0;
  }
  j["timing"] = "per tool: mean of " + std::to_string(o.builds) +
                " consecutive builds per run or sample, after one untimed build (LAMMPS: its setup); hgrid: best of its "
                "samples, taken before, between and after the other tools' runs; lammps_multi: best run of the class sets, the two fastest run 1 + " +
                std::to_string(o.lammps_reruns) + " times, on " + std::to_string(o.threads) +
                " MPI rank(s), the slowest rank's time (max of the Neigh row); cgal, embree, bullet, "
                "hgrid_new_grid: best of " +
                std::to_string(o.repeats) +
                " single builds (embree, bullet: images + build + pair finding + exact tests, their structures' "
                "release untimed); threads: embree " +
                std::to_string(o.threads) + ", bullet 1, hgrid " + std::to_string(o.threads) +
                (o.threads > 1 ? " (and 1: hgrid_one_thread, speedup_threads)" : "");
  bool agree = samples_agree;
  if (!samples_agree) j["hgrid_samples_error"] = "the samples found different pair counts";
  for (const auto& [name, s] : secs) {
    j[name] = tool(s, pairs[name], n);
    if (pairs[name] != pairs["hgrid"]) agree = false;
    if (name != "hgrid") j["ratio_vs_" + name] = s / secs["hgrid"];
  }
  if (j.contains("hgrid_new_grid_error") || j.contains("lammps_multi_pairs_error") || j.contains("embree_error") ||
      j.contains("mercurydpm_error"))
    agree = false;
  if (!open_box.empty() && open_box["hgrid"].second != open_box["mercurydpm"].second) agree = false;
  j["pairs_agree"] = agree;
  std::FILE* t = o.as_json ? stderr : stdout;
  std::fprintf(t, "n = %zu, nu = %g, %s, %s, load average %.2f; time per build (per particle), pairs, tool time / hgrid time\n",
               p.size(), o.spec.nu, o.placement.c_str(), o.boundary.c_str(), j["load_average_at_start"].get<double>());
  for (const auto& [name, s] : secs)
    std::fprintf(t, "  %-13s %10.4f s (%8.1f ns)  %12llu pairs  x%.2f\n", name.c_str(), s, 1e9 * s / n,
                 static_cast<unsigned long long>(pairs[name]), s / secs["hgrid"]);
  if (j.contains("hgrid_new_grid")) {
    const double s = j["hgrid_new_grid"]["seconds_per_build"].get<double>();
    std::fprintf(t, "  (hgrid with a new grid per build instead of one grid rebuilt: %.4f s (%.1f ns))\n", s, 1e9 * s / n);
  }
  if (!o.csv.empty()) {
    const bool fresh = !std::filesystem::exists(o.csv);
    std::FILE* f = std::fopen(o.csv.c_str(), "a");
    if (!f) throw InputError("csv", "cannot open " + o.csv);
    if (fresh) std::fprintf(f, "n,nu,placement,tool,seconds_per_build,seconds_per_particle,pairs,ratio_vs_hgrid\n");
    for (const auto& [name, s] : secs)
      std::fprintf(f, "%zu,%g,%s,%s,%.6g,%.6g,%llu,%.6g\n", p.size(), o.spec.nu, o.placement.c_str(), name.c_str(), s,
                   s / n, static_cast<unsigned long long>(pairs[name]), s / secs["hgrid"]);
    std::fclose(f);
  }
  j["load_average_at_end"] = load_average();
  if (o.as_json) std::cout << j.dump(2) << "\n";
  if (!agree) std::cerr << "peers: error: the tools disagree on the pair count\n";
  return agree ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"hgridlab vs linked cell, CGAL box_intersection_d, Embree rtcCollide, Bullet btDbvtBroadphase and LAMMPS "
               "neighbor multi/bin"};
  Options o;
  o.spec.d = 3, o.spec.nu = 0.6, o.spec.alpha = -3, o.spec.omega = 100, o.spec.progress = true;
  app.add_option("--n", o.spec.n, "number of particles")->required()->check(CLI::NonNegativeNumber);
  app.add_option("--d", o.spec.d, "dimension")->default_val(3);
  app.add_option("--nu", o.spec.nu, "packing fraction")->default_val(0.6);
  app.add_option("--alpha", o.spec.alpha, "power-law exponent")->default_val(-3.0);
  app.add_option("--omega", o.spec.omega, "r_max / r_min")->default_val(100.0);
  app.add_option("--placement", o.placement, "excluded|random")->default_val("excluded");
  app.add_option("--boundary", o.boundary, "periodic|walls")->default_val("periodic");
  app.add_option("--seed", o.spec.seed, "seed")->default_val(1)->check(CLI::NonNegativeNumber);
  app.add_option("--cache", o.cache, "packing cache directory")->default_val("results/packings");
  app.add_option("--work", o.work, "LAMMPS work directory (default results/peers/lammps-nN)");
  app.add_option("--repeats", o.repeats,
                 "CGAL, Embree, Bullet and hgridlab with a new grid per build: best of this many builds")
      ->default_val(3);
  app.add_option("--threads", o.threads,
                 "hgridlab's and Embree's threads and LAMMPS's MPI ranks (mpirun -np N); Bullet: 1 thread")
      ->default_val(1);
  app.add_option("--builds", o.builds, "timed builds per LAMMPS multi run and per hgridlab sample")->default_val(5);
  app.add_option("--bin-builds", o.bin_builds, "LAMMPS bin: timed builds")->default_val(1);
  app.add_option("--lammps-reruns", o.lammps_reruns,
                 "LAMMPS multi: runs again of each of the two fastest class sets of the scan")
      ->default_val(2);
  app.add_option("--scan", o.scan, "LAMMPS multi class scan: auto|full|small")->default_val("auto");
  app.add_option("--csv", o.csv, "append one row per tool to this CSV");
  app.add_flag("--json", o.as_json, "JSON on stdout (the table goes to stderr)");
  app.add_option("--mercurydpm", o.mercurydpm,
                 "MercuryDPM's HGrid: the mercurydpm_peer driver (default: $MERCURYDPM_BUILD/drivers/mercurydpm_peer "
                 "when built by bench/mercurydpm/build.sh; else skipped)");
  app.add_flag("--no-cgal", o.no_cgal, "skip CGAL");
  app.add_flag("--no-embree", o.no_embree, "skip Embree");
  app.add_flag("--no-bullet", o.no_bullet, "skip Bullet");
  app.add_flag("--no-lammps", o.no_lammps, "skip LAMMPS");
  app.add_flag("--no-bin", o.no_bin, "skip LAMMPS bin");
  app.add_flag("--linked-cell", o.linked_cell, "time the linked cell even above N = 2e5");
  app.add_flag("--no-linked-cell", o.no_linked_cell, "skip the linked cell");
  try {
    app.parse(argc, argv);
    return run(o);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {  // bad input exits 2, as hgrid does
    std::cerr << "peers: " << e.what() << " (see --help)\n";
    return 2;
  } catch (const InputError& e) {
    std::cerr << "peers: error: " << e.what() << "\n";
    return 2;
  }
}
