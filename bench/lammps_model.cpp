// Fits the LAMMPS multi cost model (src/model/lammps_multi.hpp) to LAMMPS
// itself: on the training packings below (none of them a figure-11 packing
// at N = 1e5 or 1e6, where `peers` judges the model's choice), runs LAMMPS
// `neighbor multi` for geometric collection sets, and fits the terms' costs.
// Writes results/lammps-model/train.csv (every run, with the fitted
// prediction) and fit.json, and prints the coefficients for
// default_lammps_coefficients(). Needs LAMMPS (`lmp`, or $HGRID_LMP).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench/lammps_run.hpp"
#include "hgridlab/advice/lammps_fit.hpp"
#include "hgridlab/io/packing_cache.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/io/lammps_export.hpp"
#include "hgridlab/io/provenance.hpp"
#include "hgridlab/model/lammps_multi.hpp"

namespace {

using namespace hgrid;

struct Training {
  std::string label;
  PackingSpec spec;
};

/// The training packings: random centres and small excluded-volume ones,
/// several omega and nu (the judged figure-11 packings are excluded volume,
/// omega = 100, N = 1e5 and 1e6).
std::vector<Training> training_set(bool quick) {
  auto spec = [](std::size_t n, Placement placement, double omega, double nu) {
    PackingSpec s;
    s.d = 3, s.n = n, s.nu = nu, s.alpha = -3, s.omega = omega, s.placement = placement, s.seed = 7;
    return s;
  };
  std::vector<Training> t{{"excluded-n50000-omega100-nu0.6", spec(50000, Placement::excluded, 100, 0.6)},
                          {"random-n100000-omega100-nu0.6", spec(100000, Placement::random, 100, 0.6)},
                          {"random-n100000-omega20-nu0.3", spec(100000, Placement::random, 20, 0.3)},
                          {"excluded-n30000-omega10-nu0.5", spec(30000, Placement::excluded, 10, 0.5)},
                          {"random-n300000-omega50-nu0.4", spec(300000, Placement::random, 50, 0.4)}};
  if (quick) t.resize(2);
  return t;
}

/// Geometric sets of k bounds from f x the smallest diameter, for the
/// k and f below; sets needing more than kMaxBins bins in a collection are
/// left out (LAMMPS takes a minute to set those up, or refuses them).
constexpr double kMaxBins = 3e7;
std::vector<std::vector<double>> candidate_sets(const Packing& p) {
  const double dmin = 2 * *std::min_element(p.radii.begin(), p.radii.end());
  const double dmax = 2 * *std::max_element(p.radii.begin(), p.radii.end());
  std::vector<std::vector<double>> out;
  for (double f : {1.0, 2.0, 4.0, 8.0, 16.0, 32.0}) {
    double bins = 1;
    for (int a = 0; a < p.d; ++a) bins *= p.box[a] / (0.5 * f * dmin) + 4;
    if (bins > kMaxBins || !(f * dmin < dmax)) continue;
    for (int k : {2, 3, 4, 6, 8}) out.push_back(geometric_collections(p, k, f * dmin));
  }
  out.push_back({dmax});
  return out;
}

std::string join(const std::vector<double>& v) {
  std::ostringstream s;
  s.precision(17);
  for (std::size_t k = 0; k < v.size(); ++k) s << (k ? " " : "") << v[k];
  return s.str();
}

struct Row {
  std::string label;
  std::size_t n;
  std::vector<double> bounds;
  LammpsSample sample;
};

/// The rows of a train.csv this program wrote (to fit again without LAMMPS).
std::vector<Row> read_rows(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw InputError("refit", "cannot read '" + path + "'");
  std::vector<Row> rows;
  std::vector<std::string> labels;
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("packing,", 0) == 0) continue;
    std::vector<std::string> cell;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cell.push_back(c);
    if (cell.size() != 5 + static_cast<std::size_t>(kLammpsTerms))
      throw InputError("refit", "'" + path + "': a row without the " + std::to_string(5 + kLammpsTerms) + " columns");
    Row r;
    r.label = cell[0];
    r.n = std::stoull(cell[1]);
    std::stringstream b(cell[2]);
    for (double v; b >> v;) r.bounds.push_back(v);
    r.sample.seconds = std::stod(cell[3]);
    std::array<double, kLammpsTerms> t{};
    for (int k = 0; k < kLammpsTerms; ++k) t[static_cast<std::size_t>(k)] = std::stod(cell[5 + static_cast<std::size_t>(k)]);
    r.sample.terms = {t[0], t[1], t[2], t[3], t[4], t[5], t[6]};
    const auto at = std::find(labels.begin(), labels.end(), r.label);
    r.sample.packing = static_cast<int>(at - labels.begin());
    if (at == labels.end()) labels.push_back(r.label);
    rows.push_back(std::move(r));
  }
  return rows;
}

std::vector<Row> measure(const std::string& out_dir, const std::string& cache, int builds, bool quick) {
  const auto lmp = find_lammps();
  if (!lmp) throw InputError("lammps", "LAMMPS not found: install Debian's lammps or set HGRID_LMP");
  std::filesystem::create_directories(out_dir);
  std::vector<Row> rows;
  int packing = -1;
  for (const auto& t : training_set(quick)) {
    ++packing;
    const Packing p = cached_packing(t.spec, cache);
    std::vector<double> diam;
    for (double r : p.radii) diam.push_back(2 * r);
    std::sort(diam.begin(), diam.end());
    const std::string work = out_dir + "/work-" + t.label;
    LammpsScript s;
    s.builds = builds;
    const auto sets = candidate_sets(p);
    for (std::size_t k = 0; k < sets.size(); ++k) {
      s.collections = sets[k];
      export_lammps(work, p, s);
      const LammpsResult r = run_lammps(*lmp, work, "in.multi.lmp", 1);
      std::fprintf(stderr, "lammps_model: %s %zu/%zu {%s}: %s\n", t.label.c_str(), k + 1, sets.size(),
                   join(sets[k]).c_str(), r.ok ? std::to_string(r.seconds_per_build()).c_str() : r.error.c_str());
      if (!r.ok) continue;
      rows.push_back({t.label, p.size(), sets[k],
                      {lammps_terms(diam, std::span<const double>(p.box.data(), static_cast<std::size_t>(p.d)), sets[k]),
                       r.seconds_per_build(), packing}});
    }
    std::filesystem::remove_all(work);
  }
  return rows;
}

int fit_and_write(const std::vector<Row>& rows, const std::string& out_dir, int builds) {
  std::filesystem::create_directories(out_dir);
  std::vector<LammpsSample> samples;
  for (const auto& r : rows) samples.push_back(r.sample);
  const LammpsFit fit = fit_lammps(samples);

  const std::string csv = out_dir + "/train.csv", tmp = csv + ".tmp";
  {
    std::ofstream f(tmp);
    f << "# " << provenance_line() << "\n"
      << "packing,n,bounds,seconds_per_build,predicted,particles,bins,lookups,stencil_same,stencil_cross,checks_same,"
         "checks_cross\n";
    f.precision(9);
    for (const auto& r : rows) {
      f << r.label << "," << r.n << "," << join(r.bounds) << "," << r.sample.seconds << ","
        << lammps_seconds(fit.coef, r.sample.terms);
      for (double v : r.sample.terms.as_array()) f << "," << v;
      f << "\n";
    }
    if (!f) throw std::runtime_error("could not write " + tmp);
  }
  std::filesystem::rename(tmp, csv);
  nlohmann::json j{{"coefficients", fit.coef.c},
                   {"stderr", fit.stderr_},
                   {"terms", {"particles", "bins", "lookups", "stencil_same", "stencil_cross", "checks_same",
                              "checks_cross"}},
                   {"rms_rel", fit.rms_rel},
                   {"max_rel", fit.max_rel},
                   {"samples", samples.size()},
                   {"builds_per_run", builds},
                   {"training", nlohmann::json::array()}};
  std::vector<std::string> labels;
  for (const auto& r : rows)
    if (std::find(labels.begin(), labels.end(), r.label) == labels.end()) labels.push_back(r.label);
  j["training"] = labels;
  for (const auto& [k, v] : provenance_fields()) j[k] = v;
  {
    std::ofstream f(out_dir + "/fit.json.tmp");
    f << j.dump(2) << "\n";
  }
  std::filesystem::rename(out_dir + "/fit.json.tmp", out_dir + "/fit.json");
  std::printf("fitted on %zu runs: rms %.1f %%, max %.1f %%\n", samples.size(), 100 * fit.rms_rel, 100 * fit.max_rel);
  std::printf("coefficients (seconds per term) for default_lammps_coefficients():\n  {");
  for (int k = 0; k < kLammpsTerms; ++k) std::printf("%s%.3g", k ? ", " : "", fit.coef.c[static_cast<std::size_t>(k)]);
  std::printf("}\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Fit the LAMMPS multi cost model to LAMMPS runs on the training packings"};
  std::string out = "results/lammps-model", cache = "results/packings";
  int builds = 5;
  bool quick = false;
  std::string refit;
  app.add_option("--out", out, "output directory")->default_val(out);
  app.add_option("--refit", refit, "fit the runs of this train.csv again instead of running LAMMPS");
  app.add_option("--cache", cache, "packing cache directory")->default_val(cache);
  app.add_option("--builds", builds, "timed neighbour-list builds per run")->default_val(5)->check(CLI::Range(1, 1000));
  app.add_flag("--quick", quick, "the first two training packings only");
  try {
    app.parse(argc, argv);
    const std::vector<Row> rows = refit.empty() ? measure(out, cache, builds, quick) : read_rows(refit);
    return fit_and_write(rows, out, builds);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const InputError& e) {
    std::cerr << "lammps_model: error: " << e.what() << "\n";
    return 2;
  }
}
