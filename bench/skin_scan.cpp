// The skin model (advice/skin_model.hpp) against a scan of skins, term by
// term: the DPM free-cooling run (2D, walls, N = 10^4, alpha = -3, omega =
// 20, nu = 0.4, e = 0.8, the scene's contact law and step) is run for
// `--steps` steps at each skin of the scan; the model, given what the list
// measured at TWO reference skins (--reference and twice it), predicts the list's length,
// the steps per build and the seconds per step at every other skin, and
// chooses a skin, which is then run too. Nothing is fitted to the scanned
// points. Prints one row per skin; the last line compares the chosen skin's
// seconds with the fastest scanned.
//   build/skin_scan [--steps 4000] [--reference 0.4] [--n 10000]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

#include "hgridlab/advice/skin_model.hpp"
#include "hgridlab/advice/skin_tuner.hpp"
#include "hgridlab/base/clock.hpp"
#include "hgridlab/dpm/simulation.hpp"
#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/packing/generate.hpp"

using namespace hgrid;

namespace {

struct Run {
  double skin, seconds_per_step, seconds_cd_per_step, candidates_per_n, steps_per_build;
  dpm::StepStats stats;
};

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t steps = 4000, n = 10000;
  double reference = 0.4;
  for (int a = 1; a + 1 < argc; a += 2) {
    if (!std::strcmp(argv[a], "--steps")) steps = std::strtoull(argv[a + 1], nullptr, 10);
    else if (!std::strcmp(argv[a], "--reference")) reference = std::atof(argv[a + 1]);
    else if (!std::strcmp(argv[a], "--n")) n = std::strtoull(argv[a + 1], nullptr, 10);
  }
  const Packing p = generate_packing({.d = 2, .n = n, .nu = 0.4, .alpha = -3, .omega = 20, .boundary = Boundary::walls,
                                      .placement = Placement::excluded, .seed = 1, .progress = false});
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> vel(p.size() * 2);
  for (auto& v : vel) v = g(rng);
  dpm::DpmConfig c;
  c.d = 2;
  c.boundary = Boundary::walls;
  c.box = p.box;
  c.contact_time = 0.05;
  c.restitution = 0.8;
  c.dt = 0.05 * c.contact_time;
  c.sizes = sizes_for_grid(choose_cell_sizes(PowerLaw(-3, 20), ModelParams{2, 0.4, 0.2, Search::top_down},
                                             CellMethod::optimal).sizes, 40.0);
  const auto run = [&](double skin) {
    c.skin = skin;
    auto sim = dpm::make_simulation(c, p, vel);
    const auto t0 = Clock::now();
    sim->run(steps);
    Run r;
    r.skin = skin;
    r.seconds_per_step = seconds_since(t0) / double(steps);
    r.stats = sim->stats();
    const auto& l = r.stats.list;
    r.seconds_cd_per_step = l.seconds() / double(l.steps);
    r.candidates_per_n = double(l.candidates_tested) / double(l.steps) / double(p.size());
    r.steps_per_build = double(l.steps) / double(l.builds);
    return r;
  };
  const auto measure = [&](const Run& r) { return skin_measurement(r.skin, r.stats.list, {}, double(p.size())); };
  const Run ref = run(reference), ref2 = run(2 * reference);
  const SkinMeasurement m = measure(ref), m2 = measure(ref2);
  const Empirical radii(p.radii);
  std::printf("# N = %zu, %llu steps per skin, reference skin %g and twice it (the model's only inputs from the scan)\n", p.size(),
              (unsigned long long)steps, reference);
  std::printf("%8s %12s %12s %12s %12s %14s %14s %14s\n", "skin", "cand/N", "model", "steps/build", "model",
              "cd s/step", "model", "shell/N model");
  double best = 1e300, best_skin = 0;
  for (const double s : {0.05, 0.1, 0.2, 0.4, 0.8, 1.0, 1.5, 2.0, 3.0, 4.0}) {
    const Run r = s == reference ? ref : s == 2 * reference ? ref2 : run(s);
    const SkinPrediction pr = predict_skin(m, m2, radii, 2, 0.4, s);
    std::printf("%8.3f %12.4f %12.4f %12.2f %12.2f %14.3e %14.3e %14.4f\n", s, r.candidates_per_n, pr.candidates_per_n,
                r.steps_per_build, pr.steps_per_build, r.seconds_cd_per_step, pr.seconds_per_step,
                shell_pairs_per_particle(radii, 2, 0.4, s));
    if (r.seconds_cd_per_step < best) best = r.seconds_cd_per_step, best_skin = s;
  }
  const SkinPrediction chosen = choose_skin(m, m2, radii, 2, 0.4, 1e-3, 4 * radii.r_max());
  const Run rc = run(chosen.skin);
  std::printf("chosen skin %.3f: contact detection %.3e s/step measured (model %.3e); fastest scanned %.3f: %.3e; "
              "ratio %.3f\n",
              chosen.skin, rc.seconds_cd_per_step, chosen.seconds_per_step, best_skin, best,
              rc.seconds_cd_per_step / best);
}
