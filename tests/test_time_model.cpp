// The time model (docs/MODEL.md section 9): its counted terms are exact, its
// expected terms follow the counts on random centres, its fit recovers known
// coefficients, its record round-trips, and --cost time refuses without one.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "hgridlab/calibration/calibrate.hpp"
#include "hgridlab/calibration/calibration.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/time_model.hpp"
#include "support.hpp"

namespace {

using namespace hgrid;
using namespace hgrid::test;
namespace fs = std::filesystem;

/// Expected terms against the counts of one random periodic packing: the
/// Poisson and moment expectations hold to this (N = 3 10^4: sampling noise
/// of a few per mille, plus the box-fitted cell sizes).
constexpr double kExpectedRelTol = 0.03;
/// Terms smaller than this fraction of N are compared absolutely.
constexpr double kSmallTermPerParticle = 0.05;
/// A fit on exact synthetic data recovers its coefficients to this.
constexpr double kFitRelTol = 1e-8;

template <int D, Boundary B>
void check_counted_terms(const Scene<D>& s, const std::vector<double>& sizes, Search search) {
  const HGrid<D, B> grid(std::span<const Sphere<D>>(s.spheres), s.box, GridParams{sizes, search});
  const Counters c = search == Search::top_down ? query_pairs<Search::top_down, Counted>(grid).second
                                                : query_pairs<Search::bottom_up, Counted>(grid).second;
  const int L = c.levels;
  std::uint64_t occupied = 0, searches = 0, rows = 0, by_level = 0;
  for (int h = 0; h < L; ++h) {
    const auto occ = grid.occupancy(h);
    occupied += occ[1] + occ[2];
    EXPECT_EQ(c.occupied_by_level[h], occ[1] + occ[2]) << "level " << h;
    // Every particle of level h searches every level below (Top-Down) or above it.
    searches += c.particles_per_level[h] * static_cast<std::uint64_t>(search == Search::top_down ? h : L - 1 - h);
    for (int j = 0; j < L; ++j) {
      by_level += c.searches_by_level[h * L + j];
      rows += c.rows_by_level[h * L + j];
    }
  }
  EXPECT_EQ(c.occupied_cells, occupied);
  EXPECT_EQ(c.searches, searches);
  EXPECT_EQ(by_level, searches);
  EXPECT_EQ(c.rows, rows);
  EXPECT_LE(c.list_checks, c.narrow_phase_checks);
}

TEST(TimeModel, CountedTermsAreExact) {
  for (std::uint64_t seed : {1u, 2u}) {
    const auto s3 = random_scene<3>(4000, 0.3, -3, 20, Boundary::periodic, seed);
    check_counted_terms<3, Boundary::periodic>(s3, exponential_sizes(4, 1, 20), Search::top_down);
    check_counted_terms<3, Boundary::periodic>(s3, exponential_sizes(4, 1, 20), Search::bottom_up);
    const auto w3 = random_scene<3>(4000, 0.3, -2, 50, Boundary::walls, seed);
    check_counted_terms<3, Boundary::walls>(w3, exponential_sizes(6, 1, 50), Search::top_down);
    const auto s2 = random_scene<2>(4000, 0.4, -3, 20, Boundary::walls, seed);
    check_counted_terms<2, Boundary::walls>(s2, exponential_sizes(5, 1, 20), Search::top_down);
  }
}

TEST(TimeModel, ExpectedTermsFollowTheCountsOnRandomCentres) {
  const std::uint64_t seed = 7;
  const auto s = random_scene<3>(30000, 0.4, -3, 20, Boundary::periodic, seed);
  std::vector<double> radii;
  double vol = 0;
  for (const auto& p : s.spheres) radii.push_back(p.r), vol += unit_ball_volume(3) * std::pow(p.r, 3);
  const double nu = vol / (s.box[0] * s.box[1] * s.box[2]);
  const Empirical dist(radii);
  const ModelParams mp{3, nu, 0.2, Search::top_down};
  const std::vector<double> sizes = sizes_for_grid(choose_cell_sizes(dist, mp, CellMethod::optimal).sizes, 40);
  const HGrid<3, Boundary::periodic> grid(std::span<const Sphere<3>>(s.spheres), s.box,
                                          GridParams{sizes, Search::top_down});
  const Counters c = grid.for_each_pair<Counted>([](std::uint32_t, std::uint32_t) {});
  const TimeTerms counted = counted_time_terms(c, build_work(grid));
  const TimeTerms expected = expected_time_terms(dist, mp, grid.sizes(), double(s.spheres.size()));
  const auto cq = query_terms(counted), eq = query_terms(expected);
  const double n = double(s.spheres.size());
  for (int k = 0; k < kQueryTerms; ++k) {
    const double tol = std::max(kExpectedRelTol * cq[k], kSmallTermPerParticle * n);
    EXPECT_NEAR(eq[k], cq[k], tol) << kQueryTermNames[k] << " (seed " << seed << ")";
  }
  EXPECT_DOUBLE_EQ(expected.level_steps, counted.level_steps);  // the same radii: the same levels
  EXPECT_NEAR(expected.directory_words, counted.directory_words, kExpectedRelTol * counted.directory_words);
}

/// Synthetic samples whose seconds are exactly sum c_k term_k.
std::vector<CalibrationSample> synthetic_samples(const TimeCoefficients& c, int d, int count) {
  std::vector<CalibrationSample> out;
  for (int i = 0; i < count; ++i) {
    CalibrationSample s;
    s.scene.packing.d = d;
    const double n = 1e4 * (1 + i % 5);
    TimeTerms& t = s.terms;
    t.particles = n;
    t.occupied_cells = n * (0.5 + 0.05 * (i % 7));
    t.run_checks = n * (1 + 3 * ((i * 5) % 11));
    t.list_checks = n * (2 + (i * 3) % 13);
    t.runs = n * (0.5 + 0.3 * ((i * 11) % 7));
    t.searches = n * 0.1 * ((i * 7) % 9);
    t.rows = n * 0.7 * ((i * 2) % 17);
    t.scanned = n * 0.01 * (i % 4);
    t.probes = n * 0.3 * ((i * 11) % 5);
    t.contacts = n * (1 + 0.5 * ((i * 7) % 5));
    t.directory_slots = n * 0.2 * ((i * 5) % 3);
    t.level_steps = n * 0.05 * (i % 6);
    t.sort_passes = n * (1 + i % 3);
    t.bucket_passes = 10 + 3 * ((i * 13) % 7);
    t.directory_words = n * 0.01 * ((i * 3) % 8);
    const PredictedSeconds p = predict_seconds(c, t);
    s.seconds = p.query;
    s.build_seconds = p.build;
    s.n = static_cast<std::size_t>(n);
    s.holdout = i % 4 == 3;
    out.push_back(s);
  }
  return out;
}

TEST(TimeModel, FitRecoversKnownCoefficients) {
  TimeCoefficients c;
  c.query = {20e-9, 5e-9, 2e-9, 3e-9, 8e-9, 15e-9, 4e-9, 6e-9, 10e-9, 7e-9};
  c.build = {20e-9, 5e-9, 9e-9, 2e-6, 30e-9, 4e-9};
  const TimeModelFit f = fit_time_model(synthetic_samples(c, 3, 48), 3);
  for (int k = 0; k < kQueryTerms; ++k) EXPECT_NEAR(f.coef.query[k], c.query[k], kFitRelTol * c.query[k]) << k;
  for (int k = 0; k < kBuildTerms; ++k) EXPECT_NEAR(f.coef.build[k], c.build[k], kFitRelTol * c.build[k]) << k;
  EXPECT_NEAR(f.query.r2_log, 1.0, 1e-9);
  EXPECT_NEAR(f.holdout_total.max_rel, 0.0, 1e-6);
  EXPECT_EQ(f.query.points, 36);
  EXPECT_EQ(f.holdout_query.points, 12);
  // No 2D samples: refused.
  EXPECT_THROW(fit_time_model(synthetic_samples(c, 3, 48), 2), std::invalid_argument);
}

TEST(TimeModel, NonNegativeFitDropsANegativeCost) {
  TimeCoefficients c;
  c.query = {20e-9, 5e-9, 2e-9, 3e-9, 8e-9, 15e-9, 4e-9, 6e-9, 10e-9, 7e-9};
  c.build = {20e-9, 5e-9, 9e-9, 2e-6, 30e-9, 4e-9};
  auto samples = synthetic_samples(c, 2, 40);
  // A term the times do not depend on, with noise that would fit negative.
  for (std::size_t i = 0; i < samples.size(); ++i) samples[i].seconds *= 1 + 0.02 * ((i % 3) - 1.0);
  const TimeModelFit f = fit_time_model(samples, 2);
  for (int k = 0; k < kQueryTerms; ++k) EXPECT_GE(f.coef.query[k], 0.0) << k;
}

TEST(TimeModel, RecordRoundTripsAndOldRecordsLoad) {
  const fs::path path = fs::temp_directory_path() / ("hgridlab_time_model_" + std::to_string(::getpid()) + ".json");
  Calibration c;
  c.K = 0.8, c.c_cell = 1.6e-9, c.c_test = 2e-9, c.points = 30, c.preset = "test";
  TimeModelFit t;
  t.coef.query = {1e-8, 2e-9, 3e-9, 4e-9, 5e-9, 6e-9, 7e-9, 8e-9, 9e-9, 1e-9};
  t.coef.build = {9e-9, 1e-9, 2e-9, 3e-6, 4e-9, 5e-9};
  t.query = {0.99, 0.05, 0.1, 30};
  t.holdout_total = {0.98, 0.07, 0.15, 18};
  c.time[1] = t;
  save_calibration(c, path.string());
  const Calibration r = load_calibration(path.string());
  ASSERT_NE(r.time_model(3), nullptr);
  EXPECT_EQ(r.time_model(2), nullptr);
  EXPECT_EQ(r.time_model(3)->coef.query, t.coef.query);
  EXPECT_EQ(r.time_model(3)->coef.build, t.coef.build);
  EXPECT_EQ(r.time_model(3)->holdout_total.points, 18);
  // A record from before the time model: K only.
  std::ofstream(path) << R"({"format": "hgridlab-calibration-1", "K": 0.7, "K_err": 0.1, "c_cell": 1e-9,
    "c_cell_err": 0, "c_test": 1e-9, "c_test_err": 0, "c0": 1e-8, "c0_err": 0, "cov_cell_test": 0,
    "r2": 0.5, "rms_rel_residual": 0.2})";
  const Calibration old = load_calibration(path.string());
  EXPECT_EQ(old.K, 0.7);
  EXPECT_EQ(old.time_model(3), nullptr);
  fs::remove(path);
}

TEST(TimeModel, TimeOptimalSizesPredictNoMoreThanTheCountOptimum) {
  TimeCoefficients c;
  c.query = {20e-9, 0, 2e-9, 3e-9, 8e-9, 20e-9, 4e-9, 6e-9, 10e-9, 7e-9};
  c.build = {20e-9, 5e-9, 9e-9, 2e-6, 30e-9, 4e-9};
  const PowerLaw dist(-3, 50);
  const ModelParams mp{3, 0.5, 0.2, Search::top_down};
  const double n = 1e5;
  const TimeOptimalSizes t = time_optimal_sizes(dist, mp, c, n);
  const auto count_opt = sizes_for_grid(choose_cell_sizes(dist, mp, CellMethod::optimal).sizes, 100);
  EXPECT_LE(t.seconds.total(), predict_seconds(c, expected_time_terms(dist, mp, count_opt, n)).total());
  EXPECT_EQ(t.sizes.back(), 100);
  for (std::size_t h = 1; h < t.sizes.size(); ++h) EXPECT_GT(t.sizes[h], t.sizes[h - 1]);
}

TEST(TimeModel, CostTimeWithoutCalibrationExits2NamingCost) {
  const fs::path missing = fs::temp_directory_path() / "hgridlab_no_calibration_here.json";
  const fs::path pk = fs::temp_directory_path() / ("hgridlab_time_" + std::to_string(::getpid()) + ".h5");
  const std::string env = "HGRID_CALIBRATION='" + missing.string() + "'";
  ASSERT_EQ(hgrid_run("generate --d 3 --n 2000 --nu 0.3 --alpha -3 --omega 10 --seed 3 --out " + pk.string(), env).status, 0);
  for (const std::string& args : std::vector<std::string>{
           "model --cost time", "count " + pk.string() + " --cells optimal --cost time", "model --cost fastest"}) {
    const Result r = hgrid_run(args, env);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_TRUE(r.out.empty()) << args;
    EXPECT_EQ(r.err.rfind("hgrid: error: cost: ", 0), 0u) << r.err;
  }
  // Without a calibration, count still runs and says there is no time model.
  const Result r = hgrid_run("count " + pk.string() + " --cells optimal --json", env);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["predicted_seconds_query_one_thread"].is_null());
  EXPECT_TRUE(j["time_model"].is_null());
  fs::remove(pk);
}

TEST(TimeModel, RecommendUsesTheCalibrationsTimeModel) {
  const fs::path dir = fs::temp_directory_path() / ("hgridlab_recommend_time_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path cal = dir / "cal.json", pk = dir / "p.h5";
  Calibration c;
  c.K = 1.2, c.c_cell = 2e-9, c.c_test = 1.6e-9, c.points = 30, c.preset = "test";
  TimeModelFit t;
  t.coef.query = {20e-9, 5e-9, 2e-9, 3e-9, 8e-9, 15e-9, 4e-9, 6e-9, 10e-9, 7e-9};
  t.coef.build = {20e-9, 5e-9, 9e-9, 2e-6, 30e-9, 4e-9};
  c.time[1] = t;
  save_calibration(c, cal.string());
  const std::string env = "HGRID_CALIBRATION='" + cal.string() + "'";
  ASSERT_EQ(hgrid_run("generate --d 3 --n 3000 --nu 0.4 --alpha -3 --omega 20 --seed 4 --out " + pk.string(), env).status, 0);
  const Result def = hgrid_run("recommend " + pk.string() + " --json", env);
  ASSERT_EQ(def.status, 0) << def.err;
  const auto j = nlohmann::json::parse(def.out);
  EXPECT_EQ(j["cost"], "time");
  EXPECT_EQ(j["K_source"], "calibration");
  EXPECT_GT(j["speedup_seconds"].get<double>(), 0.0);
  EXPECT_GT(j["predicted_seconds_query"].get<double>(), 0.0);
  // The same sizes as --cost time in count, whose sizes are the same search.
  const Result cnt = hgrid_run("recommend " + pk.string() + " --json --cost count", env);
  ASSERT_EQ(cnt.status, 0) << cnt.err;
  const auto jc = nlohmann::json::parse(cnt.out);
  EXPECT_EQ(jc["cost"], "count");
  EXPECT_TRUE(jc["speedup_seconds"].is_null());
  // A given K without --cost: the count optimum for that K.
  EXPECT_EQ(nlohmann::json::parse(hgrid_run("recommend " + pk.string() + " --json --K 0.2", env).out)["cost"], "count");
  fs::remove_all(dir);
}

}  // namespace
