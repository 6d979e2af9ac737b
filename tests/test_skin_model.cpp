// The skin model (advice/skin_model.hpp): its closed forms, and that it
// reproduces what it was given and picks the least of its own costs. Its
// check against a scan of skins is bench/skin_scan (docs/CONTACT_LIST.md).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "hgridlab/advice/skin_model.hpp"
#include "hgridlab/advice/skin_tuner.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/model/distribution.hpp"

namespace hgrid::test {
namespace {

constexpr double kClosedFormTol = 1e-12;  // relative

TEST(SkinModel, ContactValuesAreCarnahanStarlingAndHenderson) {
  EXPECT_NEAR(contact_value(3, 0.3), (1 - 0.15) / (0.7 * 0.7 * 0.7), kClosedFormTol);
  EXPECT_NEAR(contact_value(2, 0.4), (1 - 7 * 0.4 / 16) / (0.6 * 0.6), kClosedFormTol);
  EXPECT_EQ(contact_value(3, 0.0), 1.0);
  EXPECT_THROW(contact_value(3, 1.0), InputError);
  EXPECT_THROW(contact_value(4, 0.1), InputError);
}

// S(0) = 1 / (d(nu Z)/d nu) of Carnahan-Starling's and Henderson's Z.
TEST(SkinModel, StructureAtZeroIsTheEquationOfStatesCompressibility) {
  const auto Z3 = [](double x) { return (1 + x + x * x - x * x * x) / std::pow(1 - x, 3); };
  const auto Z2 = [](double x) { return (1 + x * x / 8) / std::pow(1 - x, 2); };
  for (const double nu : {0.1, 0.3, 0.55}) {
    const double h = 1e-6;
    const double d3 = ((nu + h) * Z3(nu + h) - (nu - h) * Z3(nu - h)) / (2 * h);
    const double d2 = ((nu + h) * Z2(nu + h) - (nu - h) * Z2(nu - h)) / (2 * h);
    EXPECT_NEAR(structure_at_zero(3, nu) * d3, 1.0, 1e-8) << nu;
    EXPECT_NEAR(structure_at_zero(2, nu) * d2, 1.0, 1e-8) << nu;
  }
  EXPECT_EQ(structure_at_zero(3, 0.0), 1.0);
  EXPECT_THROW(structure_at_zero(3, 1.0), InputError);
}

// Equal spheres (radius 1): the ideal gas's shell, rho / 2 (V(2 + s) -
// V(2)) with rho = nu / V(1), plus the excess E (1 - exp(-s / xi)); a thin
// shell holds g_c times the ideal gas's pairs, a thick one the ideal gas's
// plus E = (S(0) - 1 + 2^d nu) / 2.
TEST(SkinModel, ShellOfEqualSpheresIsTheIdealGasPlusTheContactExcess) {
  const Empirical ones(std::vector<double>(100, 1.0));
  for (const int d : {2, 3}) {
    const double nu = 0.3;
    const double gc = contact_value(d, nu), E = 0.5 * (structure_at_zero(d, nu) - 1 + std::pow(2.0, d) * nu);
    const double slope0 = nu / 2 * d * std::pow(2.0, d - 1);
    const double xi = E / ((gc - 1) * slope0);
    for (const double s : {0.1, 0.5, 2.0}) {
      const double bulk = nu / 2 * (std::pow(2 + s, d) - std::pow(2.0, d));
      const double want = bulk + E * (1 - std::exp(-s / xi));
      EXPECT_NEAR(shell_pairs_per_particle(ones, d, nu, s), want, 1e-9 * want) << "d " << d << ", skin " << s;
    }
    const double thin = 1e-6;
    EXPECT_NEAR(shell_pairs_per_particle(ones, d, nu, thin) / (slope0 * thin), gc, 1e-4 * gc) << d;
    const double thick = 50.0;
    EXPECT_NEAR(shell_pairs_per_particle(ones, d, nu, thick) - nu / 2 * (std::pow(2 + thick, d) - std::pow(2.0, d)), E,
                1e-6 * E) << d;
  }
  // No fluid: the ideal gas.
  EXPECT_NEAR(shell_pairs_per_particle(ones, 3, 0.0, 1.0), 0.0, 1e-15);
}

TEST(SkinModel, ReproducesItsMeasurementsAndChoosesItsOwnMinimum) {
  const PowerLaw radii(-3, 10);
  SkinMeasurement a{0.2, 6.0, 0.1, 0.3, 2e-3, 1e-3, 4e-4, 1e-4};
  SkinMeasurement b{0.4, 12.0, 0.1, 0.5, 2e-3, 1.4e-3, 5e-4, 1e-4};
  EXPECT_NEAR(predict_skin(a, b, radii, 3, 0.4, 0.2).candidates_per_n, 0.3, kClosedFormTol);
  EXPECT_NEAR(predict_skin(a, b, radii, 3, 0.4, 0.4).candidates_per_n, 0.5, kClosedFormTol);
  EXPECT_NEAR(predict_skin(a, b, radii, 3, 0.4, 0.4).steps_per_build, 12.0, kClosedFormTol);
  const SkinPrediction best = choose_skin(a, b, radii, 3, 0.4, 0.01, 5.0);
  EXPECT_GE(best.skin, 0.01);
  EXPECT_LE(best.skin, 5.0);
  for (double s = 0.01; s <= 5.0; s *= 1.05)
    EXPECT_LE(best.seconds_per_step, predict_skin(a, b, radii, 3, 0.4, s).seconds_per_step * (1 + 1e-9)) << s;
  EXPECT_THROW(predict_skin(a, a, radii, 3, 0.4, 0.3), InputError);
  // Continued below s0 the list never holds fewer pairs than the contacts.
  for (const double s : {1e-4, 1e-2, 0.1})
    EXPECT_GE(predict_skin(a, b, radii, 3, 0.6, s).candidates_per_n, 0.1) << s;
}

// A list rebuilt at every step (Monte Carlo sweeps) measured its steps per
// build at their floor, 1: the travel per step it measured sets k(s) = s /
// travel instead; a measurement with more steps per build keeps k(s0) s / s0.
TEST(SkinModel, EveryStepRebuildsTakeTheMeasuredTravel) {
  const PowerLaw radii(-3, 10);
  SkinMeasurement a{0.2, 1.0, 0.1, 0.3, 2e-3, 1e-3, 4e-4, 1e-4};
  SkinMeasurement b{0.4, 1.0, 0.1, 0.5, 2e-3, 1.4e-3, 5e-4, 1e-4};
  a.travel_per_step = b.travel_per_step = 0.8;
  EXPECT_NEAR(predict_skin(a, b, radii, 3, 0.4, 0.4).steps_per_build, 1.0, kClosedFormTol);
  EXPECT_NEAR(predict_skin(a, b, radii, 3, 0.4, 2.4).steps_per_build, 3.0, kClosedFormTol);
  b.travel_per_step = 0;  // not measured: ballistic from k(s1)
  EXPECT_NEAR(predict_skin(a, b, radii, 3, 0.4, 2.4).steps_per_build, 6.0, kClosedFormTol);
  b.steps_per_build = 3.0, b.travel_per_step = 0.8;  // not censored: k(s1) s / s1
  EXPECT_NEAR(predict_skin(a, b, radii, 3, 0.4, 2.4).steps_per_build, 18.0, kClosedFormTol);
}

// With the displacements' growth from one step to two measured (g), k(s) =
// (s / travel)^(1 / b), b = log2 g held between a random walk's 1/2 and
// straight lines' 1.
TEST(SkinModel, EveryStepRebuildsTakeTheDisplacementsGrowth) {
  const PowerLaw radii(-3, 10);
  SkinMeasurement a{0.2, 1.0, 0.1, 0.3, 2e-3, 1e-3, 4e-4, 1e-4, 0.8};
  SkinMeasurement b{0.4, 1.0, 0.1, 0.5, 2e-3, 1.4e-3, 5e-4, 1e-4, 0.8};
  const auto k = [&](double growth) {
    a.travel_growth = b.travel_growth = growth;
    return predict_skin(a, b, radii, 3, 0.4, 2.4).steps_per_build;
  };
  EXPECT_NEAR(k(2.0), 3.0, kClosedFormTol);
  EXPECT_NEAR(k(std::sqrt(2.0)), 9.0, 1e-9);
  EXPECT_NEAR(k(std::pow(2.0, 0.75)), std::pow(3.0, 1 / 0.75), 1e-9);
  EXPECT_NEAR(k(1.1), 9.0, 1e-9);  // slower than a random walk: held at it
  EXPECT_NEAR(k(3.0), 3.0, kClosedFormTol);  // faster than straight lines: held at them
}

// skin = "auto" (advice/skin_tuner.hpp): the first skin a tenth of the mean
// diameter; nothing until a window of builds has passed; the first window's
// skin doubled; then the model's choice from the two windows, which is
// choose_skin's on the same measurements.
TEST(SkinTuner, DoublesTheFirstSkinThenTakesTheModelsChoice) {
  const std::vector<double> r = {1.0, 2.0, 3.0, 4.0};
  EXPECT_NEAR(SkinTuner::first_skin(r), 0.5, kClosedFormTol);
  SkinTuner tuner(3, 2);
  ContactListStats s;
  // Window 1 at skin 0.5: 20 steps, 2 builds.
  s.steps = 10, s.builds = 1, s.contacts = 4, s.candidates_tested = 120;
  s.seconds_grid = 1e-3, s.seconds_build = 2e-3, s.seconds_test = 1e-3, s.seconds_check = 5e-4;
  EXPECT_FALSE(tuner.after_build(s, 0.5, r, 0.4));
  s.steps = 20, s.builds = 2, s.candidates_tested = 240;
  s.seconds_grid = 2e-3, s.seconds_build = 4e-3, s.seconds_test = 2e-3, s.seconds_check = 1e-3;
  const auto second = tuner.after_build(s, 0.5, r, 0.4);
  ASSERT_TRUE(second);
  EXPECT_DOUBLE_EQ(*second, 1.0);
  EXPECT_FALSE(tuner.predicted());
  // Window 2 at skin 1.0: 40 more steps, 2 builds, longer lists.
  s.steps = 60, s.builds = 4, s.candidates_tested = 240 + 40 * 16;
  s.seconds_grid = 4e-3, s.seconds_build = 9e-3, s.seconds_test = 2e-3 + 40 * 1.5e-4, s.seconds_check = 3e-3;
  const auto third = tuner.after_build(s, 1.0, r, 0.4);
  ASSERT_TRUE(third && tuner.predicted());
  const SkinMeasurement a{0.5, 10.0, 1.0, 3.0, 1e-3, 1e-3, 1e-4, 5e-5};
  const SkinMeasurement b{1.0, 20.0, 1.0, 4.0, 1e-3, 1.5e-3, 1.5e-4, 5e-5};
  const Empirical dist(r);
  const SkinPrediction want = choose_skin(a, b, dist, 3, 0.4, 1e-3 * dist.r_min(), 4 * dist.r_max());
  EXPECT_NEAR(*third, want.skin, kClosedFormTol * want.skin);
  EXPECT_THROW(SkinTuner(4), InputError);
  EXPECT_THROW(SkinTuner(3, 0), InputError);
  EXPECT_THROW(tuner.after_build(s, 1.0, r, 1.0), InputError);
}

}  // namespace
}  // namespace hgrid::test
