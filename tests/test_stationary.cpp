// An equilibration that stops when stationary: the test on a series, and
// the generator's runs with stop = stationary (the same chain as a run of
// fixed sweeps, cut where the test passes; the same for any thread count;
// resumed bit for bit; no overlaps, nu exact).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <span>
#include <unistd.h>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/packing/detail/gen_record.hpp"
#include "hgridlab/packing/detail/gen_stationary.hpp"
#include "hgridlab/packing/generate.hpp"
#include "hgridlab/packing/identity.hpp"

#include "killed_run.hpp"
#include "support.hpp"

namespace hgrid {
namespace {

constexpr std::uint64_t kStationarySeed = 20140901;
using test::kNuTol;

TEST(Stationary, ConstantAndNoisySeriesPass) {
  using detail::kStationaryMinSamples;
  std::vector<double> flat(kStationaryMinSamples - 1, 10.0);
  EXPECT_FALSE(detail::test_stationary(flat, kStationaryRelTol, kStationaryMinSamples).stationary)
      << "fewer samples than the minimum";
  flat.push_back(10.0);
  EXPECT_TRUE(detail::test_stationary(flat, kStationaryRelTol, kStationaryMinSamples).stationary);
  std::mt19937_64 rng(kStationarySeed);  // seeded: white noise of 0.1 % around 10
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<double> noisy;
  for (int i = 0; i < 400; ++i) noisy.push_back(10.0 + noise(rng));
  const auto t = detail::test_stationary(noisy, kStationaryRelTol, detail::kStationaryMinSamples);
  EXPECT_TRUE(t.stationary) << "drift " << t.drift << ", se " << t.se;
  EXPECT_EQ(t.samples, 200u);
}

TEST(Stationary, DriftBeyondNoiseAndToleranceFails) {
  // A logarithmic relaxation, 0.2 % per doubling, no noise: measured exactly.
  const auto at = [](std::size_t k) { return std::log(static_cast<double>((k + 1) * detail::kStationarySampleSweeps)); };
  std::vector<double> drift;
  for (std::size_t k = 0; k < 400; ++k) drift.push_back(10.0 + 0.02 / std::log(2.0) * at(k));
  const auto t = detail::test_stationary(drift, kStationaryRelTol, detail::kStationaryMinSamples);
  EXPECT_FALSE(t.stationary);
  EXPECT_NEAR(t.drift, 0.02, 1e-9);
  // 0.02 % per doubling is within the tolerance (0.1 %).
  std::vector<double> slow;
  for (std::size_t k = 0; k < 400; ++k) slow.push_back(10.0 + 0.002 / std::log(2.0) * at(k));
  EXPECT_TRUE(detail::test_stationary(slow, kStationaryRelTol, detail::kStationaryMinSamples).stationary);
  // A linear drift of 1 % over the run: 0.5 % over its second half.
  std::vector<double> linear;
  for (std::size_t k = 0; k < 400; ++k) linear.push_back(10.0 * (1 + 1e-2 * static_cast<double>(k) / 400));
  EXPECT_FALSE(detail::test_stationary(linear, kStationaryRelTol, detail::kStationaryMinSamples).stationary);
  // Noise hides no drift: 1 % noise around a constant fails (it would need
  // far more samples), where the drift alone is zero.
  std::mt19937_64 rng(kStationarySeed);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<double> noisy;
  for (int i = 0; i < 400; ++i) noisy.push_back(10.0 + noise(rng));
  EXPECT_FALSE(detail::test_stationary(noisy, kStationaryRelTol, detail::kStationaryMinSamples).stationary);
}

/// Stationary before its cap under a tolerance of 1 % (the figures' 0.1 %
/// needs N ~ 10^5); small_spec's, at the default tolerance, runs to its cap.
constexpr double kLooseTol = 1e-2;
PackingSpec stationary_spec(int d, Boundary b, int threads) {
  PackingSpec s;
  s.d = d;
  s.n = 2000;
  s.nu = 0.3;
  s.alpha = -3;
  s.omega = 2;
  s.stationary_tol = kLooseTol;
  s.boundary = b;
  s.placement = Placement::excluded;
  s.seed = kStationarySeed;
  s.equilibrate = true;
  s.stop = EquilibrationStop::stationary;
  s.sweeps = 400;  // the cap
  s.threads = threads;
  s.progress = false;
  return s;
}

PackingSpec small_spec(int d, Boundary b) {
  PackingSpec s = stationary_spec(d, b, 1);
  s.n = 1500;
  s.nu = 0.45;
  s.omega = 5;
  s.sweeps = 150;
  s.stationary_tol = kStationaryRelTol;
  return s;
}

// A noisy small packing runs to its cap, not stationary, and is the chain
// of fixed sweeps.
TEST(Stationary, NoisyPackingRunsToItsCap) {
  for (const auto& [d, b] : std::vector<std::pair<int, Boundary>>{{3, Boundary::walls}, {2, Boundary::periodic}}) {
    SCOPED_TRACE("d " + std::to_string(d) + " " + to_string(b) + " seed " + std::to_string(kStationarySeed));
    const PackingSpec s = small_spec(d, b);
    const Packing p = generate_packing(s);
    EXPECT_EQ(equilibration_sweeps_done(p), 150u);
    EXPECT_EQ(p.num_attrs.at("stationarity_reached"), 0.0);
    EXPECT_EQ(packing_mismatch(p, s), "");
    PackingSpec fixed = s;
    fixed.stop = EquilibrationStop::sweeps;
    EXPECT_EQ(generate_packing(fixed).positions, p.positions);
    EXPECT_EQ(assess_packing(p, nullptr).max_rel_overlap, 0.0);
  }
}

// The run that stopped is the chain of fixed sweeps cut at its stop: the
// same positions as a stop = sweeps run of exactly that many sweeps.
TEST(Stationary, StopsOnTheSameChainAndIsExact) {
  for (const auto& [d, b] : std::vector<std::pair<int, Boundary>>{{3, Boundary::periodic}, {2, Boundary::walls}}) {
    SCOPED_TRACE("d " + std::to_string(d) + " " + to_string(b) + " seed " + std::to_string(kStationarySeed));
    const PackingSpec s = stationary_spec(d, b, 1);
    const Packing p = generate_packing(s);
    const std::uint64_t done = equilibration_sweeps_done(p);
    EXPECT_GE(done, stationary_floor(s) * detail::kStationarySampleSweeps);
    EXPECT_LT(done, 400u) << "should be stationary well before the cap";
    EXPECT_EQ(done % detail::kStationarySampleSweeps, 0u);
    EXPECT_EQ(p.num_attrs.at("stationarity_reached"), 1.0);
    EXPECT_EQ(p.str_attrs.at("equilibration_stop"), "stationary");
    EXPECT_EQ(p.str_attrs.at("cache_key"), packing_key(s));
    EXPECT_EQ(packing_mismatch(p, s), "");
    EXPECT_EQ(assess_packing(p, nullptr).max_rel_overlap, 0.0);
    EXPECT_NEAR(p.packing_fraction() / s.nu, 1.0, kNuTol);
    PackingSpec fixed = s;
    fixed.stop = EquilibrationStop::sweeps;
    fixed.sweeps = static_cast<int>(done);
    const Packing q = generate_packing(fixed);
    EXPECT_EQ(p.positions, q.positions);
    EXPECT_NE(packing_key(fixed), packing_key(s));
    // The same for any number of threads (5 oversubscribes 2 cores).
    for (const int t : {2, 5}) {
      const Packing m = generate_packing(stationary_spec(d, b, t));
      EXPECT_EQ(m.positions, p.positions) << t << " threads";
      EXPECT_EQ(m.str_attrs.at("stationarity_series"), p.str_attrs.at("stationarity_series"));
    }
  }
}

// Event chains may stop from their own floor (60 sweeps, not the
// Metropolis moves' 120): the floor is part of the packing's identity, the
// decision is the first sample at which the recorded series passes the test
// with that floor, and the packing is the chain of fixed sweeps cut there.
TEST(Stationary, EventChainsStopFromTheirOwnFloor) {
  PackingSpec s = stationary_spec(3, Boundary::periodic, 1);
  s.moves = EquilibrationMoves::event_chain;
  s.stationary_tol = 5 * kLooseTol;  // 2000 spheres are noisy: loose enough to pass between the two floors
  ASSERT_EQ(stationary_floor(s), detail::kStationaryMinSamplesEventChain);
  ASSERT_LT(detail::kStationaryMinSamplesEventChain, detail::kStationaryMinSamples);
  PackingSpec metropolis = s;
  metropolis.moves = EquilibrationMoves::metropolis;
  EXPECT_EQ(stationary_floor(metropolis), detail::kStationaryMinSamples);
  EXPECT_NE(packing_key(s).find(",min=30)"), std::string::npos) << packing_key(s);
  EXPECT_NE(packing_key(metropolis).find(",min=60)"), std::string::npos) << packing_key(metropolis);
  const Packing p = generate_packing(s);
  const std::uint64_t done = equilibration_sweeps_done(p);
  EXPECT_EQ(p.num_attrs.at("stationarity_reached"), 1.0);
  EXPECT_GE(done, detail::kStationaryMinSamplesEventChain * detail::kStationarySampleSweeps);
  EXPECT_LT(done, detail::kStationaryMinSamples * detail::kStationarySampleSweeps)
      << "a loose tolerance should pass before the Metropolis floor";
  const auto series = *detail::recorded_series(p);
  ASSERT_EQ(series.size(), done / detail::kStationarySampleSweeps);
  for (std::size_t n = 1; n < series.size(); ++n)
    EXPECT_FALSE(detail::test_stationary(std::span(series).first(n), s.stationary_tol, stationary_floor(s)).stationary)
        << "passed at sample " << n;
  EXPECT_EQ(p.str_attrs.at("stationarity_rule"), detail::stationarity_rule(s.stationary_tol, stationary_floor(s)));
  PackingSpec fixed = s;
  fixed.stop = EquilibrationStop::sweeps;
  fixed.sweeps = static_cast<int>(done);
  EXPECT_EQ(generate_packing(fixed).positions, p.positions);
}

// Killed part-way (a checkpoint after every sweep, killed after the 37th:
// not a sample sweep), resumed: the uninterrupted run, bit for bit, with
// the same decision.
TEST(Stationary, ResumedRunTakesTheSameDecision) {
  PackingSpec s = stationary_spec(2, Boundary::periodic, 1);
  const Packing whole = generate_packing(s);
  const std::vector<Packing> checkpoints = test::checkpoints_until_killed(s, 37);
  ASSERT_EQ(checkpoints.size(), 37u);
  EXPECT_EQ(resume_mismatch(checkpoints.back(), s), "");
  const Packing resumed = generate_packing(s, &checkpoints.back());
  EXPECT_EQ(resumed.positions, whole.positions);
  EXPECT_EQ(resumed.str_attrs.at("stationarity_series"), whole.str_attrs.at("stationarity_series"));
  EXPECT_EQ(equilibration_sweeps_done(resumed), equilibration_sweeps_done(whole));
  // A checkpoint whose series was lost cannot be resumed.
  Packing lost = checkpoints.back();
  lost.str_attrs.erase("stationarity_series");
  EXPECT_NE(resume_mismatch(lost, s), "");
}

// The series travels with the packing's file: a checkpoint written to
// HDF5 and read back (in a child process, as the cache reads) resumes to the
// uninterrupted run. Until 2026-12-06 the series was written but not read
// back, so `--from` refused such a file and a killed run's cached
// checkpoint was passed over: its Monte Carlo started again.
TEST(Stationary, ResumesThroughItsFile) {
  PackingSpec s = stationary_spec(2, Boundary::periodic, 1);
  const Packing whole = generate_packing(s);
  const std::vector<Packing> checkpoints = test::checkpoints_until_killed(s, 37);
  ASSERT_EQ(checkpoints.size(), 37u);
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("hgrid_stationary_" + std::to_string(::getpid()) + ".h5");
  write_packing(file.string(), checkpoints.back());
  const Packing read = read_packing(file.string(), Isolation::child_process);
  std::filesystem::remove(file);
  for (const char* k : {"stationarity_series", "stationarity_rule"})
    EXPECT_EQ(read.str_attrs.at(k), checkpoints.back().str_attrs.at(k)) << k;
  EXPECT_EQ(read.num_attrs.at("stationarity_reached"), checkpoints.back().num_attrs.at("stationarity_reached"));
  EXPECT_EQ(resume_mismatch(read, s), "");
  const Packing resumed = generate_packing(s, &read);
  EXPECT_EQ(resumed.positions, whole.positions);
  EXPECT_EQ(resumed.str_attrs.at("stationarity_series"), whole.str_attrs.at("stationarity_series"));
  EXPECT_EQ(equilibration_sweeps_done(resumed), equilibration_sweeps_done(whole));
}

TEST(Stationary, StopNeedsAnEquilibration) {
  PackingSpec s = stationary_spec(3, Boundary::periodic, 1);
  s.equilibrate = false;
  EXPECT_THROW(generate_packing(s), InputError);
  EXPECT_THROW(parse_equilibration_stop("soon"), InputError);
  EXPECT_EQ(parse_equilibration_stop("stationary"), EquilibrationStop::stationary);
  s.equilibrate = true;
  for (const double tol : {0.0, -1e-3, 0.2, std::nan("")}) {
    s.stationary_tol = tol;
    EXPECT_THROW(generate_packing(s), InputError) << tol;
  }
  // The tolerance is part of the packing's identity.
  PackingSpec other = stationary_spec(3, Boundary::periodic, 1);
  other.stationary_tol = 2e-2;
  EXPECT_NE(packing_key(other), packing_key(stationary_spec(3, Boundary::periodic, 1)));
}

}  // namespace
}  // namespace hgrid
