// Benchmark (b) of the contact list (docs/CONTACT_LIST.md): a polydisperse
// pour that LAMMPS ran (experiments/beds/in.pour_bench, after LAMMPS's
// examples/pour/in.pour), its dump written at every step of a window and
// replayed here. Every frame's exact contact set (pairs with distance <
// r_i + r_j; every axis walled) is found, timed three ways on one thread over
// the same frames:
//   - the grid rebuilt every frame, with the fastest of the paper's sizes for
//     nu = 0.1 ... 0.7, the linked cell and the density field's
//     recommendation (the baseline);
//   - the contact list at every skin of a scan (absolute skins, the dump's
//     length unit), with the baseline's sizes;
//   - the contact list at the skin model's choice (advice/skin_model.hpp),
//     given what the list measured at two reference skins only;
//   - the contact list with skin = "auto" (advice/skin_tuner.hpp: the model
//     applied as the run goes, from a first skin of a tenth of the mean
//     diameter).
// Also the list's build (grid of the inflated spheres + candidate search +
// storing the list) per build at --lammps-skin, to set beside LAMMPS's
// neighbour time per build on the same window (experiments/beds/
// pour_bench.sh). Particles poured during the window join the list as new
// indices (the dump is sorted by id). In the first round every frame's
// pairs are compared with a fresh grid's, and --brute frames (spread over
// the window) with an O(N^2) search; exit status 1 on any difference.
//   build/pour_replay DUMP [--rounds 3] [--reference 0.05] [--lammps-skin 0.2]
//                          [--brute 3] [--first F] [--frames K] [--list-sizes NAME]
//                          [--profile-skin S]  (only the list at skin S, --rounds times)
//                          [--trace 1]  (skin = "auto"'s choices on stderr)
//                          [--threads T]  (every pass on T threads; default 1)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "hgridlab/advice/recommend.hpp"
#include "hgridlab/advice/skin_model.hpp"
#include "hgridlab/advice/skin_tuner.hpp"
#include "hgridlab/base/clock.hpp"
#include "hgridlab/contacts/contact_list.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/model/density_field.hpp"

#include "detail/skin_measurement.hpp"

using namespace hgrid;
using bench::ListRun;

namespace {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

struct Frame {
  long step = 0;
  std::vector<double> x, r;  // N x 3 (from the box's lower corner), N
};

/// The frames of a LAMMPS dump `custom ... id type x y z radius`, sorted by
/// id; the box's lower corner and largest sides over the frames.
std::vector<Frame> read_dump(const std::string& path, std::array<double, 3>& lo, std::array<double, 3>& side,
                             std::size_t first, std::size_t count) {
  std::ifstream in(path);
  if (!in) {
    std::fprintf(stderr, "pour_replay: cannot read %s\n", path.c_str());
    std::exit(2);
  }
  std::vector<Frame> frames;
  std::string line;
  std::size_t index = 0;
  bool have_box = false;
  while (std::getline(in, line)) {
    if (line != "ITEM: TIMESTEP") continue;
    Frame f;
    std::getline(in, line);
    f.step = std::atol(line.c_str());
    std::getline(in, line);  // ITEM: NUMBER OF ATOMS
    std::getline(in, line);
    const std::size_t n = std::strtoull(line.c_str(), nullptr, 10);
    std::getline(in, line);  // ITEM: BOX BOUNDS
    std::array<double, 3> blo{}, bhi{};
    for (int k = 0; k < 3; ++k) {
      std::getline(in, line);
      std::istringstream(line) >> blo[k] >> bhi[k];
    }
    std::getline(in, line);  // ITEM: ATOMS id type x y z radius
    const bool keep = index >= first && index < first + count;
    if (keep) f.x.resize(3 * n), f.r.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      std::getline(in, line);
      if (!keep) continue;
      char* p = line.data();
      std::strtol(p, &p, 10);
      std::strtol(p, &p, 10);
      for (int k = 0; k < 3; ++k) f.x[3 * i + k] = std::strtod(p, &p);
      f.r[i] = std::strtod(p, &p);
    }
    if (keep) {
      if (!have_box) lo = blo;
      for (int k = 0; k < 3; ++k) side[k] = std::max(have_box ? side[k] : 0.0, bhi[k] - lo[k]);
      have_box = true;
      for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) f.x[3 * i + k] -= lo[k];
      frames.push_back(std::move(f));
    }
    ++index;
  }
  return frames;
}

std::vector<Sphere<3>> spheres_of(const Frame& f) {
  std::vector<Sphere<3>> s(f.r.size());
  for (std::size_t i = 0; i < f.r.size(); ++i) s[i] = {{f.x[3 * i], f.x[3 * i + 1], f.x[3 * i + 2]}, f.r[i]};
  return s;
}

Pairs sorted(Pairs p) {
  for (auto& [i, j] : p)
    if (i > j) std::swap(i, j);
  std::sort(p.begin(), p.end());
  return p;
}

Pairs fresh_pairs(const Frame& f, const Extent<3>& box, const std::vector<double>& sizes) {
  const auto s = spheres_of(f);
  HGrid<3, Boundary::walls> g(s, box, GridParams{sizes, Search::bottom_up});
  Pairs out;
  g.for_each_pair([&](std::uint32_t i, std::uint32_t j) { out.emplace_back(i, j); });
  return sorted(std::move(out));
}

/// Every pair with distance < r_i + r_j, the grid's expression (no images:
/// every axis walled).
Pairs brute_pairs(const Frame& f) {
  Pairs out;
  const std::size_t n = f.r.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      double s = 0;
      for (int k = 0; k < 3; ++k) {
        const double d = f.x[3 * j + k] - f.x[3 * i + k];
        s += d * d;
      }
      const double c = f.r[i] + f.r[j];
      if (s < c * c) out.emplace_back(std::uint32_t(i), std::uint32_t(j));
    }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: pour_replay DUMP [--rounds 3] [--reference 0.05] [--lammps-skin 0.2] [--brute 3] "
                 "[--first F] [--frames K]\n");
    return 2;
  }
  const std::string path = argv[1];
  std::uint64_t rounds = 3, brute = 3, first = 0, count = ~std::uint64_t{0} / 2;
  double reference = 0.05, lammps_skin = 0.2, profile_skin = 0;
  bool trace = false;
  int threads = 1;
  std::string list_sizes_name;
  for (int a = 2; a + 1 < argc; a += 2) {
    if (!std::strcmp(argv[a], "--rounds")) rounds = std::strtoull(argv[a + 1], nullptr, 10);
    else if (!std::strcmp(argv[a], "--reference")) reference = std::atof(argv[a + 1]);
    else if (!std::strcmp(argv[a], "--lammps-skin")) lammps_skin = std::atof(argv[a + 1]);
    else if (!std::strcmp(argv[a], "--brute")) brute = std::strtoull(argv[a + 1], nullptr, 10);
    else if (!std::strcmp(argv[a], "--first")) first = std::strtoull(argv[a + 1], nullptr, 10);
    else if (!std::strcmp(argv[a], "--frames")) count = std::strtoull(argv[a + 1], nullptr, 10);
    else if (!std::strcmp(argv[a], "--profile-skin")) profile_skin = std::atof(argv[a + 1]);
    else if (!std::strcmp(argv[a], "--list-sizes")) list_sizes_name = argv[a + 1];
    else if (!std::strcmp(argv[a], "--trace")) trace = std::atoi(argv[a + 1]) != 0;
    else if (!std::strcmp(argv[a], "--threads")) threads = std::max(1, std::atoi(argv[a + 1]));
    else {
      std::fprintf(stderr, "pour_replay: unknown option %s\n", argv[a]);
      return 2;
    }
  }
  std::array<double, 3> lo{}, side{};
  const std::vector<Frame> frames = read_dump(path, lo, side, first, count);
  if (frames.size() < 2) {
    std::fprintf(stderr, "pour_replay: %s: fewer than 2 frames\n", path.c_str());
    return 2;
  }
  const Extent<3> box{side[0], side[1], side[2]};
  const ListBox<3> lbox{{side[0], side[1], side[2]}, {0, 0, 0}, {false, false, false}};
  const Frame& last = frames.back();
  const Empirical dist(last.r);
  const double r_min = dist.r_min();

  // The sizes scanned for the grid rebuilt every frame, and the field's.
  std::map<std::string, std::vector<double>> sized = bench::scanned_sizes(dist);
  const DensityField field(last.x, last.r, FieldBox{3, side, {false, false, false}});
  const Recommendation rec = recommend_for_field(field, ModelParams{3, field.box_nu(), 0.2, Search::bottom_up});
  sized["field"] = rec.sizes;
  // The skin model's shell: the particles' mean local nu (as skin="auto" takes it).
  const double nu_local = std::min(field.summary(6 * dist.r_max()).mean_nu, 0.95);

  const auto rebuild_pass = [&](const std::vector<double>& sizes) {
    std::vector<Sphere<3>> s = spheres_of(frames[0]);
    HGrid<3, Boundary::walls> g(s, box, GridParams{sizes, Search::bottom_up, threads});
    std::vector<std::uint64_t> contacts(8 * static_cast<std::size_t>(threads));  // a cache line per thread
    const auto t0 = Clock::now();
    for (const Frame& f : frames) {
      s.resize(f.r.size());
      for (std::size_t i = 0; i < s.size(); ++i) s[i] = {{f.x[3 * i], f.x[3 * i + 1], f.x[3 * i + 2]}, f.r[i]};
      g.rebuild(s);
      if (threads <= 1) g.for_each_pair<PairsOnly>([&](std::uint32_t, std::uint32_t) { ++contacts[0]; });
      else g.for_each_pair<PairsOnly>([&](int t, std::uint32_t, std::uint32_t) { ++contacts[8 * std::size_t(t)]; });
    }
    return seconds_since(t0) / double(frames.size());
  };
  // The baseline's sizes, chosen once by a first (untimed for the record) pass.
  std::string base_name = "linked cell";
  if (profile_skin <= 0) {
    double best = 1e300;
    for (const auto& [name, sizes] : sized) {
      const double s = rebuild_pass(sizes);
      if (s < best) best = s, base_name = name;
    }
  }
  if (!list_sizes_name.empty() && !sized.count(list_sizes_name)) {
    std::fprintf(stderr, "pour_replay: --list-sizes: one of");
    for (const auto& [name, sizes] : sized) std::fprintf(stderr, " '%s'", name.c_str());
    std::fprintf(stderr, "\n");
    return 2;
  }
  const std::vector<double> list_sizes = sized[list_sizes_name.empty() ? base_name : list_sizes_name];
  std::uint64_t mismatches = 0, checked = 0, brute_checked = 0;
  const auto list_pass = [&](double skin, bool check) {
    ContactList<3> list(lbox, ContactListParams{list_sizes, Search::bottom_up, threads, skin, 0.0});
    ListRun r;
    double seconds = 0;
    const std::size_t brute_every = brute ? std::max<std::size_t>(1, frames.size() / brute) : 0;
    for (std::size_t t = 0; t < frames.size(); ++t) {
      const auto t0 = Clock::now();
      list.update(frames[t].x, frames[t].r);
      list.for_each_contact([&](std::uint32_t, std::uint32_t) { ++r.contacts; });
      seconds += seconds_since(t0);
      if (check) {
        Pairs got;
        list.for_each_contact([&](std::uint32_t i, std::uint32_t j) { got.emplace_back(i, j); });
        got = sorted(std::move(got));
        mismatches += got != fresh_pairs(frames[t], box, list_sizes);
        ++checked;
        if (brute_every && (t % brute_every == brute_every / 2)) mismatches += got != brute_pairs(frames[t]), ++brute_checked;
      }
    }
    r.seconds_per_step = seconds / double(frames.size());
    r.stats = list.stats();
    return r;
  };
  const auto measurement = [&](double skin, const ListRun& r) {
    return skin_measurement(skin, r.stats, {}, double(last.r.size()));
  };

  if (profile_skin > 0) {  // only the list at one skin, untimed passes (for a profiler)
    for (std::uint64_t round = 0; round < rounds; ++round) {
      const ListRun r = list_pass(profile_skin, false);
      const double builds = double(std::max<std::uint64_t>(1, r.stats.builds));
      const double steps = double(std::max<std::uint64_t>(1, r.stats.steps));
      std::printf("skin %g, sizes %s: %.3e s/frame, %.3e s/build (grid %.3e), %llu builds, per frame check %.3e test "
                  "%.3e, %.2f candidates per particle\n",
                  profile_skin, list_sizes_name.empty() ? base_name.c_str() : list_sizes_name.c_str(),
                  r.seconds_per_step, r.stats.seconds_build / builds, r.stats.seconds_grid / builds,
                  (unsigned long long)r.stats.builds, r.stats.seconds_check / steps, r.stats.seconds_test / steps,
                  double(r.stats.candidates_tested) / steps / double(last.r.size()));
    }
    return 0;
  }
  // The model's skin from two reference skins (their own passes).
  const double s0 = reference, s1 = 2 * reference;
  const SkinMeasurement m0 = measurement(s0, list_pass(s0, false)), m1 = measurement(s1, list_pass(s1, false));
  const SkinPrediction chosen = choose_skin(m0, m1, dist, 3, nu_local, 1e-3 * r_min, 4 * dist.r_max());
  if (trace)
    for (const SkinMeasurement& m : {m0, m1})
      std::fprintf(stderr,
                   "pour_replay: measured skin %.4g: %.2f steps/build, L/N %.3f, grid %.3e + store %.3e per build, test "
                   "%.3e + check %.3e per step; predicted there %.3e s/step\n",
                   m.skin, m.steps_per_build, m.candidates_per_n, m.seconds_grid, m.seconds_store, m.seconds_test,
                   m.seconds_check, predict_skin(m0, m1, dist, 3, nu_local, m.skin).seconds_per_step);

  // skin = "auto": the tuner (advice/skin_tuner.hpp) from its first skin on,
  // re-chosen every few builds, as Python's ContactList(skin="auto") runs.
  double auto_skin_final = 0;
  const auto auto_pass = [&]() {
    ContactList<3> list(lbox, ContactListParams{list_sizes, Search::bottom_up, threads, SkinTuner::first_skin(frames[0].r), 0.0});
    SkinTuner tuner(3);
    double seconds = 0;
    std::uint64_t contacts = 0;
    for (const Frame& f : frames) {
      const auto t0 = Clock::now();
      if (list.update(f.x, f.r))
        if (const auto next = tuner.after_build(list.stats(), list.params().skin, f.r, nu_local)) {
          if (trace)
            std::fprintf(stderr, "pour_replay: step %ld, skin %.4g -> %.4g (predicted %.3e s/step, %.1f steps/build)\n",
                         f.step, list.params().skin, *next, tuner.predicted() ? tuner.predicted()->seconds_per_step : 0.0,
                         tuner.predicted() ? tuner.predicted()->steps_per_build : 0.0);
          list.set_skin(*next);
        }
      list.for_each_contact([&](std::uint32_t, std::uint32_t) { ++contacts; });
      seconds += seconds_since(t0);
    }
    auto_skin_final = list.params().skin;
    return seconds / double(frames.size());
  };

  // Timed passes, alternated over rounds, the fastest of each kept.
  std::vector<double> scan = {0.0125, 0.025, 0.05, 0.1, 0.2, 0.4, 0.8};
  if (std::find(scan.begin(), scan.end(), lammps_skin) == scan.end()) scan.push_back(lammps_skin);
  std::sort(scan.begin(), scan.end());
  double base = 1e300;
  std::map<double, ListRun> list_best;
  double chosen_best = 1e300, auto_best = 1e300;
  for (std::uint64_t round = 0; round < rounds; ++round) {
    auto_best = std::min(auto_best, auto_pass());
    base = std::min(base, rebuild_pass(list_sizes));
    for (double s : scan) {
      const ListRun r = list_pass(s, round == 0);
      if (!list_best.count(s) || r.seconds_per_step < list_best[s].seconds_per_step) list_best[s] = r;
    }
    chosen_best = std::min(chosen_best, list_pass(chosen.skin, false).seconds_per_step);
    std::fprintf(stderr, "pour_replay: round %llu of %llu done\n", (unsigned long long)round + 1,
                 (unsigned long long)rounds);
  }
  std::printf("# %s: %zu frames (steps %ld..%ld), %zu -> %zu spheres, diameters %.3g..%.3g, box %.4g x %.4g x %.4g "
              "(walls), box nu %.3f, mean local nu %.3f; fastest of %llu alternated rounds, %d thread(s)\n",
              path.c_str(), frames.size(), frames.front().step, frames.back().step, frames.front().r.size(),
              last.r.size(), 2 * r_min, 2 * dist.r_max(), side[0], side[1], side[2], field.box_nu(), nu_local,
              (unsigned long long)rounds, threads);
  std::printf("# grid rebuilt every frame: fastest sizes %s (%zu levels), %.3e s/frame\n", base_name.c_str(),
              list_sizes.size(), base);
  std::printf("%8s %12s %10s %12s %10s %14s\n", "skin", "s/frame", "speed-up", "frames/build", "cand/N", "s/build");
  double best = 1e300, best_skin = 0;
  for (double s : scan) {
    const ListRun& r = list_best[s];
    const auto& l = r.stats;
    const double builds = double(std::max<std::uint64_t>(1, l.builds));
    std::printf("%8.4f %12.3e %10.2f %12.1f %10.3f %14.3e\n", s, r.seconds_per_step, base / r.seconds_per_step,
                double(l.steps) / builds, double(l.candidates_tested) / double(l.steps) / double(last.r.size()),
                l.seconds_build / builds);
    if (r.seconds_per_step < best) best = r.seconds_per_step, best_skin = s;
  }
  std::printf("model's skin %.4f (from %.4g and %.4g): %.3e s/frame, %.3f of the fastest scanned (skin %.4g), "
              "speed-up %.2f over the rebuilt grid\n",
              chosen.skin, s0, s1, chosen_best, chosen_best / best, best_skin, base / chosen_best);
  std::printf("skin=\"auto\" (first skin %.4g, re-chosen every %llu builds; last %.4f): %.3e s/frame, %.3f of the "
              "fastest scanned, speed-up %.2f over the rebuilt grid\n",
              SkinTuner::first_skin(frames[0].r), (unsigned long long)SkinTuner::kBuildsPerWindow, auto_skin_final,
              auto_best, auto_best / best, base / auto_best);
  const ListRun& at = list_best[lammps_skin];
  std::printf("list build at skin %g: %.3e s per build (grid %.3e + search and store %.3e), %llu builds in %llu frames\n",
              lammps_skin, at.stats.seconds_build / double(std::max<std::uint64_t>(1, at.stats.builds)),
              at.stats.seconds_grid / double(std::max<std::uint64_t>(1, at.stats.builds)),
              (at.stats.seconds_build - at.stats.seconds_grid) / double(std::max<std::uint64_t>(1, at.stats.builds)),
              (unsigned long long)at.stats.builds, (unsigned long long)at.stats.steps);
  std::printf("pairs: %llu frames against a fresh grid, %llu against brute force: %llu mismatches\n",
              (unsigned long long)checked, (unsigned long long)brute_checked, (unsigned long long)mismatches);
  return mismatches == 0 ? 0 : 1;
}
