// The LAMMPS multi cost model (model/lammps_multi.hpp) and its fit
// (advice/lammps_fit.hpp): terms counted by hand on a small case, the
// choice of bounds scale-free and well formed, the fit recovering known
// coefficients, a bad coefficients file refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "hgridlab/advice/lammps_fit.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/model/lammps_multi.hpp"
#include "support.hpp"

namespace hgrid::test {
namespace {

constexpr double kTermsRelTol = 1e-12;
/// The same diameters and box in another (power-of-two) unit: the same
/// doubles in units of the smallest diameter, so the same bounds exactly.
constexpr double kScaleRelTol = 1e-12;

/// 2D box of side 10, four particles of diameter 1, one collection c = 1:
/// bins of 0.5 (20 per axis) plus 2 ceil(1 / 0.5) + 2 = 6 for the ghost
/// layer: 26^2 bin heads. Pair cutoff 1 = 2 bins: the stencil is all 5 x 5
/// offsets (the farthest, (2, 2), is 0.5 * sqrt(2) < 1 away), the half
/// stencil 12 + the own bin; 4 x 0.25 / 100 = 0.01 particles per bin.
TEST(LammpsModel, TermsByHand) {
  const std::vector<double> diam{1, 1, 1, 1}, box{10, 10}, bounds{1};
  const LammpsTerms t = lammps_terms(diam, box, bounds);
  EXPECT_EQ(t.particles, 4);
  EXPECT_EQ(t.lookups, 4);
  EXPECT_EQ(t.bins, 26 * 26);
  EXPECT_NEAR(t.stencil_same, 4 * 13, kTermsRelTol * 52);
  EXPECT_NEAR(t.checks_same, 4 * 13 * 0.01, kTermsRelTol);
  EXPECT_EQ(t.stencil_cross, 0);
  EXPECT_EQ(t.checks_cross, 0);
}

/// Two collections in 3D: the small particles search the large ones' bins
/// (side 2 for c = 4 in a box of 20) within (1 + 4) / 2 = 2.5 = 1.25 bins:
/// offsets up to 2 per axis whose nearest bin is within 2.5: every offset
/// with at most... counted here by brute force over the bin corners.
TEST(LammpsModel, CrossStencilMatchesABruteForceCount) {
  const std::vector<double> diam{1, 1, 4}, box{20, 20, 20}, bounds{1, 4};
  const LammpsTerms t = lammps_terms(diam, box, bounds);
  // Brute force: bins of side 2 around the central bin [0,2)^3; a bin at
  // offset o is in the stencil when its nearest point to the central bin is
  // within 2.5.
  int n = 0;
  for (int x = -3; x <= 3; ++x)
    for (int y = -3; y <= 3; ++y)
      for (int z = -3; z <= 3; ++z) {
        double g2 = 0;
        for (int o : {x, y, z}) {
          const double g = o == 0 ? 0.0 : 2.0 * (std::abs(o) - 1);
          g2 += g * g;
        }
        n += g2 <= 2.5 * 2.5;
      }
  EXPECT_NEAR(t.stencil_cross, 2.0 * n, kTermsRelTol * n);
  EXPECT_NEAR(t.checks_cross, 2.0 * n * (1 * 8.0 / 8000), kTermsRelTol * n);
  EXPECT_EQ(t.lookups, 6);
}

std::vector<double> power_law_diameters(std::size_t n, double omega, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> d(n);
  // alpha = -3: r = (1 - u (1 - omega^-2))^(-1/2)
  for (auto& x : d) x = 2 / std::sqrt(1 - u(rng) * (1 - 1 / (omega * omega)));
  std::sort(d.begin(), d.end());
  return d;
}

TEST(LammpsModel, ChoiceIsWellFormedAndScaleFree) {
  constexpr std::uint64_t kSeed = 5;
  const std::vector<double> diam = power_law_diameters(20000, 50, kSeed), box{400, 400, 400};
  const LammpsCoefficients c = default_lammps_coefficients();
  const LammpsChoice a = lammps_collections(diam, box, c);
  ASSERT_GE(a.bounds.size(), 2u);
  EXPECT_LE(a.bounds.size(), static_cast<std::size_t>(kLammpsMaxCollections));
  EXPECT_EQ(a.bounds.back(), diam.back());
  EXPECT_GE(a.bounds.front(), diam.front());
  for (std::size_t k = 1; k < a.bounds.size(); ++k) EXPECT_GT(a.bounds[k], a.bounds[k - 1]);
  // No single changed bound (by the search's smallest step) is predicted faster.
  const double best = lammps_seconds(c, lammps_terms(diam, box, a.bounds));
  EXPECT_NEAR(a.seconds, best, kTermsRelTol * best);
  for (std::size_t h = 0; h + 1 < a.bounds.size(); ++h)
    for (double f : {1.0442737824274138, 1 / 1.0442737824274138}) {
      std::vector<double> b = a.bounds;
      b[h] *= f;
      if ((h > 0 && b[h] <= b[h - 1]) || b[h] >= b[h + 1] || b[h] < diam.front()) continue;
      EXPECT_GE(lammps_seconds(c, lammps_terms(diam, box, b)), best * (1 - kTermsRelTol)) << "bound " << h;
    }
  // In a unit 1/64 of this one.
  std::vector<double> diam64(diam), box64(box);
  for (double& x : diam64) x *= 64;
  for (double& x : box64) x *= 64;
  const LammpsChoice b = lammps_collections(diam64, box64, c);
  ASSERT_EQ(b.bounds.size(), a.bounds.size());
  for (std::size_t k = 0; k < a.bounds.size(); ++k) EXPECT_NEAR(b.bounds[k], 64 * a.bounds[k], kScaleRelTol * b.bounds[k]);
}

TEST(LammpsModel, OneSizeGivesOneCollection) {
  const std::vector<double> diam(5000, 3.0), box{100, 100, 100};
  const LammpsChoice a = lammps_collections(diam, box, default_lammps_coefficients());
  ASSERT_EQ(a.bounds.size(), 1u);
  EXPECT_EQ(a.bounds[0], 3.0);
}

/// Builds priced by known coefficients plus a constant per packing: the fit
/// gives them back (all but stencil_same, which no set changes here).
TEST(LammpsModel, FitRecoversKnownCoefficients) {
  const LammpsCoefficients truth{{0, 7e-10, 9e-9, 0, 1.2e-9, 2.5e-9, 3.5e-9}};
  const std::vector<double> constant{0.004, 0.011};
  std::vector<LammpsSample> samples;
  for (int p = 0; p < 2; ++p) {
    const std::vector<double> diam = power_law_diameters(p ? 8000 : 3000, p ? 30 : 80, 11 + p),
                              box{p ? 300.0 : 250.0, p ? 300.0 : 250.0, p ? 300.0 : 250.0};
    for (double first : {2.0, 4.0, 8.0, 16.0})
      for (int L : {2, 3, 4, 6}) {
        std::vector<double> b(static_cast<std::size_t>(L));
        for (int h = 0; h < L; ++h)
          b[static_cast<std::size_t>(h)] = first * diam.front() * std::pow(diam.back() / (first * diam.front()), h / double(L - 1));
        b.back() = diam.back();
        const LammpsTerms t = lammps_terms(diam, box, b);
        samples.push_back({t, lammps_seconds(truth, t) + constant[static_cast<std::size_t>(p)], p});
      }
  }
  const LammpsFit f = fit_lammps(samples);
  for (int k : {1, 2, 4, 5, 6})
    EXPECT_NEAR(f.coef.c[static_cast<std::size_t>(k)], truth.c[static_cast<std::size_t>(k)],
                1e-6 * truth.c[static_cast<std::size_t>(k)])
        << "term " << k;
  EXPECT_LT(f.rms_rel, 1e-9);
}

/// The shipped coefficients are the fit of the shipped training runs
/// (results/lammps-model/train.csv, written by bench/lammps_model): refitting
/// them gives default_lammps_coefficients() to the 6 digits it is written with.
TEST(LammpsModel, DefaultCoefficientsAreTheFitOfTheShippedRuns) {
  constexpr double kPrintedRelTol = 1e-5;
  std::ifstream f(std::string(HGRID_SOURCE_DIR) + "/results/lammps-model/train.csv");
  ASSERT_TRUE(f) << "results/lammps-model/train.csv";
  std::vector<LammpsSample> samples;
  std::vector<std::string> packings;
  for (std::string line; std::getline(f, line);) {
    if (line.empty() || line[0] == '#' || line.rfind("packing,", 0) == 0) continue;
    std::vector<std::string> cell;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cell.push_back(c);
    ASSERT_EQ(cell.size(), 12u) << line;
    const auto at = std::find(packings.begin(), packings.end(), cell[0]);
    if (at == packings.end()) packings.push_back(cell[0]);
    LammpsSample s;
    s.packing = static_cast<int>(std::find(packings.begin(), packings.end(), cell[0]) - packings.begin());
    s.seconds = std::stod(cell[3]);
    s.terms = {std::stod(cell[5]), std::stod(cell[6]), std::stod(cell[7]), std::stod(cell[8]),
               std::stod(cell[9]), std::stod(cell[10]), std::stod(cell[11])};
    samples.push_back(s);
  }
  EXPECT_EQ(packings.size(), 5u);
  const LammpsFit fit = fit_lammps(samples);
  const LammpsCoefficients shipped = default_lammps_coefficients();
  for (std::size_t k = 0; k < shipped.c.size(); ++k)
    EXPECT_NEAR(fit.coef.c[k], shipped.c[k], kPrintedRelTol * shipped.c[k]) << "term " << k;
}

TEST(LammpsModel, CoefficientsFileFromTheEnvironment) {
  const std::string good = ::testing::TempDir() + "lammps_fit_good.json",
                    bad = ::testing::TempDir() + "lammps_fit_bad.json";
  std::ofstream(good) << R"({"coefficients": [0, 1e-9, 0, 0, 1e-9, 2e-9, 3e-9]})";
  std::ofstream(bad) << R"({"coefficients": [0, -1, 0]})";
  std::string source;
  ::setenv("HGRID_LAMMPS_MODEL", good.c_str(), 1);
  EXPECT_EQ(lammps_coefficients(&source).c[5], 2e-9);
  EXPECT_EQ(source, good);
  ::setenv("HGRID_LAMMPS_MODEL", bad.c_str(), 1);
  EXPECT_THROW(lammps_coefficients(), InputError);
  ::unsetenv("HGRID_LAMMPS_MODEL");
  EXPECT_EQ(lammps_coefficients(&source).c, default_lammps_coefficients().c);
  EXPECT_EQ(source, "default");
}

}  // namespace
}  // namespace hgrid::test
