// hgrid calibrate: measure this machine's K (cell access time / overlap test
// time) on the calibration scenes and store it for `--K auto`.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common.hpp"
#include "hgridlab/io/atomic_file.hpp"
#include "hgridlab/calibration/calibrate.hpp"
#include "hgridlab/base/error.hpp"

namespace hgrid::cli {
namespace {

struct CalibrateArgs {
  bool quick = false, json = false, holdout = true;
  std::string out, csv;
};

/// The samples as CSV with "# key=value" parameter lines (for plots/calibration.gp).
void write_samples_csv(const std::string& path, const CalibrationRun& run) {
  const Calibration& c = run.result;
  write_stream_atomically(path, [&](std::ostream& f) {
    f.precision(10);
    f << "# hgridlab calibration scenes: query wall time (best of repeats) and counts\n"
      << "# K=" << c.K << "\n# K_err=" << c.K_err << "\n# c0=" << c.c0 << "\n# c_cell=" << c.c_cell
      << "\n# c_test=" << c.c_test << "\n# r2=" << c.r2 << "\n# machine=" << c.machine << "\n# date=" << c.date
      << "\n# git_hash=" << c.git_hash << "\n# compiler=" << c.compiler << "\n# preset=" << c.preset << "\n";
    f << "label,d,placement,boundary,alpha,omega,nu,cells,K_sizes,n,levels,cell_accesses,narrow_phase_checks,"
         "contacts,seconds,repeats,T_K02,T_Kcal,W_fit,holdout,build_seconds";
    for (const auto name : kQueryTermNames) f << ",q_" << name;
    for (const auto name : kBuildTermNames) f << ",b_" << name;
    f << ",time_model_query,time_model_build\n";
    for (const auto& s : run.samples) {
      const auto& p = s.scene.packing;
      const double A = double(s.accesses), C = double(s.checks);
      f << s.scene.label() << ',' << p.d << ',' << to_string(p.placement) << ',' << to_string(p.boundary)
        << ',' << p.alpha << ',' << p.omega << ',' << p.nu << ',' << s.scene.cells << ',' << s.scene.K_sizes << ','
        << s.n << ',' << s.levels << ',' << s.accesses << ',' << s.checks << ',' << s.contacts << ',' << s.seconds
        << ',' << s.repeats << ',' << C + 0.2 * A << ',' << C + c.K * A << ','
        << c.c0 * double(s.n) + c.c_cell * A + c.c_test * C << ',' << (s.holdout ? 1 : 0) << ',' << s.build_seconds;
      for (const double v : query_terms(s.terms)) f << ',' << v;
      for (const double v : build_terms(s.terms)) f << ',' << v;
      const TimeModelFit* t = c.time_model(p.d);
      const PredictedSeconds ps = t ? predict_seconds(t->coef, s.terms) : PredictedSeconds{};
      f << ',' << ps.query << ',' << ps.build << "\n";
    }
  }, "csv");
}

void run(const CalibrateArgs& a) {
  const std::string path = a.out.empty() ? calibration_path() : a.out;
  CalibrateOptions opt;
  opt.quick = a.quick;
  opt.holdout = a.holdout;
  if (a.quick) {
    opt.timing = TimingOptions{2, 20, 0.1};
    opt.passes = 1;
  }
  const auto t0 = std::chrono::steady_clock::now();
  opt.progress = [&](std::size_t done, std::size_t total, const CalibrationSample& s) {
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double rate = double(done) / el;
    std::fprintf(stderr, "hgrid calibrate: %zu/%zu scene timings (%.0f%%), %.2g/s, ETA %.0f s | %s: %.4g ms\n", done,
                 total, 100.0 * double(done) / double(total), rate, double(total - done) / rate,
                 s.scene.label().c_str(), 1e3 * s.seconds);
  };
  const CalibrationRun run = run_calibration(opt);
  const Calibration& c = run.result;
  if (!(std::isfinite(c.K) && c.K > 0))
    throw std::runtime_error("the fit gave K = " + std::to_string(c.K) + " (not > 0); nothing stored");
  save_calibration(c, path);
  if (!a.csv.empty()) write_samples_csv(a.csv, run);
  if (a.json) {
    std::ifstream in(path);
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(in);
    j["path"] = path;
    j["samples"] = nlohmann::json::array();
    for (const auto& s : run.samples)
      j["samples"].push_back({{"label", s.scene.label()}, {"holdout", s.holdout}, {"n", s.n},
                              {"levels", s.levels}, {"cell_accesses", s.accesses},
                              {"narrow_phase_checks", s.checks}, {"contacts", s.contacts},
                              {"seconds", s.seconds}, {"build_seconds", s.build_seconds},
                              {"repeats", s.repeats}});
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::printf("K = %.4g +- %.2g   (cell access time / overlap test time; the paper uses 0.2)\n", c.K, c.K_err);
  std::printf("c_cell = %.4g +- %.2g ns per cell access\n", 1e9 * c.c_cell, 1e9 * c.c_cell_err);
  std::printf("c_test = %.4g +- %.2g ns per narrow-phase check\n", 1e9 * c.c_test, 1e9 * c.c_test_err);
  std::printf("c0     = %.4g +- %.2g ns per particle\n", 1e9 * c.c0, 1e9 * c.c0_err);
  std::printf("R^2 = %.5f, rms relative residual %.1f %%, %d scenes (%s)\n", c.r2, 100 * c.rms_rel_residual, c.points,
              c.preset.c_str());
  std::printf("single-K fit: R^2 of ln W = %.3f\n", c.r2_log);
  for (int d = 2; d <= 3; ++d) {
    if (!c.time_model(d)) continue;
    const TimeModelFit& t = *c.time_model(d);
    std::printf("%dD time model (ns per unit):", d);
    for (int k = 0; k < kQueryTerms; ++k)
      std::printf(" %s %.3g", std::string(kQueryTermNames[k]).c_str(), 1e9 * t.coef.query[k]);
    std::printf(" | build:");
    for (int k = 0; k < kBuildTerms; ++k)
      std::printf(" %s %.3g", std::string(kBuildTermNames[k]).c_str(), 1e9 * t.coef.build[k]);
    std::printf("\n");
    const auto show = [](const char* what, const FitQuality& q) {
      std::printf("  %-22s R^2(ln W) = %.3f, rms %.1f %%, max %.1f %% (%d scenes)\n", what, q.r2_log, 100 * q.rms_rel,
                  100 * q.max_rel, q.points);
    };
    show("query, fitted:", t.query);
    show("build, fitted:", t.build);
    show("build + query, fitted:", t.total);
    show("query, held out:", t.holdout_query);
    show("build + query, held out:", t.holdout_total);
  }
  std::printf("machine: %s\nstored in %s\n", c.machine.c_str(), path.c_str());
}

}  // namespace

void register_calibrate_commands(CLI::App& app) {
  auto a = std::make_shared<CalibrateArgs>();
  auto* sub = app.add_subcommand(
      "calibrate",
      "measure this machine's K (cell access time / overlap test time) and store it for --K auto");
  sub->add_flag("--quick", a->quick, "fewer, smaller scenes and repeats (~4x faster, larger error)");
  sub->add_flag("!--no-holdout", a->holdout, "skip the held-out scenes (measured to judge the time model, not fitted)");
  sub->add_flag("--json", a->json, "print the stored record and every scene's sample as JSON");
  sub->add_option("--out", a->out,
                  "store here instead of $HGRID_CALIBRATION or ${XDG_CONFIG_HOME:-~/.config}/hgridlab/calibration.json");
  sub->add_option("--csv", a->csv, "also write every scene's counts and wall time to this CSV");
  sub->callback([a] { run(*a); });
}

}  // namespace hgrid::cli
