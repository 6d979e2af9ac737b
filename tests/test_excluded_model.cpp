// The excluded-volume cost model: its Percus-Yevick core against closed
// forms, its limits, its discretisation, and values computed independently.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/model/detail/py_mixture.hpp"
#include "hgridlab/model/detail/py_numeric.hpp"
#include "hgridlab/model/detail/walls.hpp"
#include "hgridlab/model/detail/window.hpp"
#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/excluded.hpp"

namespace hgrid {
namespace {

constexpr double kPyRelTol = 1e-9;           // closed forms vs the Q-matrix route at k -> 0
constexpr double kLowDensityRelTol = 1e-9;   // issue target: nu -> 0 equals the paper model
constexpr double kDiscretisationRelTol = 1e-3;
constexpr double kIndependentAbsTol = 2e-3;  // vs the numpy/LAPACK evaluation, per particle
constexpr double kWallBulkRelTol = 2e-3;     // per 1000 units of box length, walled vs bulk
constexpr double kIndependentWallRelTol = 3e-4;  // walled T/N vs the numpy evaluation (each ~1e-4)
constexpr double kPyNumericRelTol = 2e-3;    // numerical PY (r step 1/80 diameter) vs closed-form contact values
constexpr double kVirialAbsTol = 3e-4;       // 2D contact value at eta = 0.01 vs its first order in density

double excess(const Distribution& d, double nu, const std::vector<double>& s, const ExcludedOptions& o = {}) {
  const ModelParams p{3, nu, 0.2, Search::top_down};
  return evaluate_excluded_model(d, p, s, o).T_cd_over_N - evaluate_model(d, p, s).T_cd_over_N;
}

TEST(PyMixture, MonodisperseStructureFactorAtZeroK) {
  // S(0) = (1 - eta)^4 / (1 + 2 eta)^2 (Percus-Yevick compressibility).
  for (double eta : {0.1, 0.3, 0.5, 0.6}) {
    const double rho = eta * 6.0 / std::numbers::pi;
    const detail::PyMixture py({rho}, {1.0});
    std::vector<std::vector<double>> y;
    py.apply_h(1e-5, {{1.0}}, y);
    const double S0 = 1.0 + y[0][0];
    EXPECT_NEAR(S0, std::pow(1 - eta, 4) / std::pow(1 + 2 * eta, 2), kPyRelTol) << "eta " << eta;
  }
}

TEST(PyMixture, BinaryCompressibilityMatchesScaledParticlePressure) {
  // d(beta P)/d rho_j = sum_i sqrt(rho_i / rho_j) (I + H)^{-1}_ij, with beta P
  // the Percus-Yevick compressibility (scaled-particle) pressure of the mixture.
  const std::vector<double> rho = {0.3, 0.02}, sig = {1.0, 3.0};
  const auto betaP = [&](std::vector<double> r) {
    double xi[4] = {0, 0, 0, 0};
    for (int n = 0; n < 4; ++n)
      for (int i = 0; i < 2; ++i) xi[n] += std::numbers::pi / 6 * r[i] * std::pow(sig[i], n);
    const double e = 1 - xi[3];
    return 6 / std::numbers::pi * (xi[0] / e + 3 * xi[1] * xi[2] / (e * e) + 3 * std::pow(xi[2], 3) / std::pow(e, 3));
  };
  const detail::PyMixture py(rho, sig);
  std::vector<std::vector<double>> y;
  py.apply_h(1e-5, {{1.0, 0.0}, {0.0, 1.0}}, y);
  // (I + H) as a 2x2 matrix; invert it.
  const double a = 1 + y[0][0], b = y[1][0], c = y[0][1], d = 1 + y[1][1], det = a * d - b * c;
  const double inv[2][2] = {{d / det, -b / det}, {-c / det, a / det}};
  for (int j = 0; j < 2; ++j) {
    double lhs = 0;
    for (int i = 0; i < 2; ++i) lhs += std::sqrt(rho[i] / rho[j]) * inv[i][j];
    std::vector<double> r2 = rho;
    const double eps = 1e-7 * rho[j];
    r2[j] += eps;
    std::vector<double> r1 = rho;
    r1[j] -= eps;
    EXPECT_NEAR(lhs, (betaP(r2) - betaP(r1)) / (2 * eps), 1e-5 * lhs) << "component " << j;
  }
}

detail::PyNumericGrid fine_grid(double range) {
  detail::PyNumericGrid g;
  g.dr = 1.0 / 80;
  g.range = range;
  g.nk = static_cast<int>(30 * range / std::numbers::pi);
  g.r_out = 2.0;
  return g;
}

TEST(PyNumeric, SpheresReproduceTheClosedFormContactValues) {
  // The numerical scheme in 3D against Percus-Yevick's closed forms: g(sigma+)
  // = (1 + eta/2) / (1 - eta)^2, and Lebowitz's mixture contact values.
  for (double eta : {0.3, 0.5}) {
    const detail::PyNumeric py(3, {eta * 6 / std::numbers::pi}, {1.0}, fine_grid(16));
    EXPECT_NEAR(py.contact_value(0, 0) / ((1 + eta / 2) / std::pow(1 - eta, 2)), 1.0, kPyNumericRelTol) << eta;
  }
  const std::vector<double> rho = {0.3, 0.02}, sig = {1.0, 3.0};
  double x2 = 0, x3 = 0;
  for (int i = 0; i < 2; ++i) x2 += std::numbers::pi / 6 * rho[i] * sig[i] * sig[i], x3 += std::numbers::pi / 6 * rho[i] * std::pow(sig[i], 3);
  const detail::PyNumeric py(3, rho, sig, fine_grid(48));
  for (int a = 0; a < 2; ++a)
    for (int b = a; b < 2; ++b) {
      const double exact = 1 / (1 - x3) + 3 * x2 / std::pow(1 - x3, 2) * sig[a] * sig[b] / (sig[a] + sig[b]);
      EXPECT_NEAR(py.contact_value(a, b) / exact, 1.0, kPyNumericRelTol) << a << b;
    }
}

TEST(PyNumeric, DiscsAtLowDensityFollowTheFirstOrderInDensity) {
  // To first order in rho, g(r) = 1 + rho A(r) outside contact, with A(r) the
  // overlap area of two discs of radius sigma at distance r (exact, and
  // Percus-Yevick is exact to that order): A(sigma) = sigma^2 (2 pi / 3 - sqrt(3) / 2).
  const double eta = 0.01, rho = eta * 4 / std::numbers::pi;
  const detail::PyNumeric py(2, {rho}, {1.0}, fine_grid(16));
  EXPECT_NEAR(py.contact_value(0, 0), 1 + rho * (2 * std::numbers::pi / 3 - std::sqrt(3.0) / 2), kVirialAbsTol);
}

TEST(ExcludedWindow, ShellAreasIntegrateToTheWindowVolume) {
  const double c = 7.5, s = 6.0, dr = 0.01;
  const int nmax = static_cast<int>(std::sqrt(3.0) * (c + s) / dr) + 2;
  const auto A = detail::window_shell_areas(c, s, dr, nmax);
  double v = 0;
  for (int n = 1; n <= nmax; ++n) v += A[n] * dr;
  EXPECT_NEAR(v, std::pow(2 * c + s, 3), 1e-3 * std::pow(2 * c + s, 3));
}

TEST(ExcludedWindow, SineTransformMatchesTheDirectSum) {
  std::vector<double> x(64);
  for (std::size_t m = 0; m < x.size(); ++m) x[m] = std::cos(0.3 * m) + 0.01 * m;
  std::vector<double> y = x;
  detail::sine_transform(y);
  for (std::size_t n = 1; n < x.size(); ++n) {
    double s = 0;
    for (std::size_t m = 1; m < x.size(); ++m) s += x[m] * std::sin(std::numbers::pi * m * n / x.size());
    EXPECT_NEAR(y[n], s, 1e-10 * x.size());
  }
}

TEST(ExcludedModel, LowDensityEqualsThePaperModel) {
  const PowerLaw d(-3, 10);
  const std::vector<double> s = {4.0, 8.0, 20.0};
  const ModelParams p{3, 1e-10, 0.2, Search::top_down};
  const double paper = evaluate_model(d, p, s).T_over_N, ex = evaluate_excluded_model(d, p, s).T_over_N;
  EXPECT_NEAR(ex / paper, 1.0, kLowDensityRelTol);
}

TEST(ExcludedWindow, CircleLengthsIntegrateToTheWindowArea) {
  const double c = 7.5, s = 6.0, dr = 0.01;
  const int nmax = static_cast<int>(std::sqrt(2.0) * (c + s) / dr) + 2;
  const auto L = detail::window_circle_lengths(c, s, dr, nmax);
  double a = 0;
  for (int n = 1; n <= nmax; ++n) a += L[n] * dr;
  EXPECT_NEAR(a, std::pow(2 * c + s, 2), 1e-3 * std::pow(2 * c + s, 2));
}

TEST(ExcludedModel, DiscsAtLowDensityEqualThePaperModel) {
  const PowerLaw d(-3, 10);
  const std::vector<double> s = {4.0, 8.0, 20.0};
  const ModelParams p{2, 1e-10, 0.2, Search::top_down};
  EXPECT_NEAR(evaluate_excluded_model(d, p, s).T_over_N / evaluate_model(d, p, s).T_over_N, 1.0, kLowDensityRelTol);
}

TEST(ExcludedModel, DiscsConvergedInTheirDiscretisation) {
  const PowerLaw d(-3, 10);
  const std::vector<double> s = {4.0, 8.0, 20.0};
  const ModelParams p{2, 0.5, 0.2, Search::top_down};
  const double ref = evaluate_excluded_model(d, p, s).T_over_N;
  std::vector<ExcludedOptions> finer(4);
  finer[0].disc_bins_per_level = 8;
  finer[1].disc_dr = 0.02;
  finer[2].disc_range = 6;
  finer[3].k_max = 30;
  for (const ExcludedOptions& o : finer)
    EXPECT_NEAR(evaluate_excluded_model(d, p, s, o).T_over_N / ref, 1.0, kDiscretisationRelTol)
        << o.disc_bins_per_level << " " << o.disc_dr << " " << o.disc_range << " " << o.k_max;
}

TEST(ExcludedModel, ConvergedInItsDiscretisation) {
  const PowerLaw d(-3, 10);
  const std::vector<double> s = {4.0, 8.0, 20.0};
  const ModelParams p{3, 0.5, 0.2, Search::top_down};
  const double ref = evaluate_excluded_model(d, p, s).T_over_N;
  std::vector<ExcludedOptions> finer(3);
  finer[0].bins_per_level = 12;
  finer[1].k_max = 30;
  finer[2].dk = 0.25;
  for (const ExcludedOptions& o : finer)
    EXPECT_NEAR(evaluate_excluded_model(d, p, s, o).T_over_N / ref, 1.0, kDiscretisationRelTol)
        << o.bins_per_level << " " << o.k_max << " " << o.dk;
}

TEST(ExcludedModel, MatchesAnIndependentEvaluation) {
  // Excess of T_cd/N over the paper model from a separate numpy/LAPACK
  // implementation (k-space window transforms, LAPACK inverse of Q^T Q):
  // python3 tests/independent/excluded_pins.py reproduces these numbers.
  struct Case { double alpha, omega, nu; std::vector<double> sizes; double excess; };
  const std::vector<Case> cases = {{-3, 10, 0.4, {4, 8, 20}, 0.618382},
                                   {-3, 100, 0.6, {6, 14, 30, 70, 200}, 2.551228},
                                   {0, 10, 0.5, {5, 12, 20}, -0.184327}};
  for (const Case& c : cases)
    EXPECT_NEAR(excess(PowerLaw(c.alpha, c.omega), c.nu, c.sizes), c.excess, kIndependentAbsTol)
        << "alpha " << c.alpha << " omega " << c.omega << " nu " << c.nu;
}

TEST(ExcludedModel, DiscsMatchAnIndependentEvaluation) {
  // Excess of T_cd/N over the paper model from a separate numpy evaluation
  // (J0 by series and Hankel's expansion, Simpson inside contact on per-pair
  // grids, plain Picard mixing): python3 tests/independent/excluded_pins_2d.py
  // reproduces these numbers (~6 min).
  struct Case { double alpha, omega, nu; std::vector<double> sizes; double excess; };
  const std::vector<Case> cases = {{-3, 10, 0.4, {4, 8, 20}, -0.156092},
                                   {-3, 10, 0.6, {4, 8, 20}, 0.092627},
                                   {0, 5, 0.5, {3, 10}, -0.350251}};
  for (const Case& c : cases) {
    const PowerLaw d(c.alpha, c.omega);
    const ModelParams p{2, c.nu, 0.2, Search::top_down};
    const double e = evaluate_excluded_model(d, p, c.sizes).T_cd_over_N - evaluate_model(d, p, c.sizes).T_cd_over_N;
    EXPECT_NEAR(e, c.excess, kIndependentAbsTol) << "alpha " << c.alpha << " omega " << c.omega << " nu " << c.nu;
  }
}

TEST(ExcludedModel, DenseEdgesStayFinite) {
  // alpha = -1 and -d-1 (special cases of the power law), omega -> 1, nu near
  // random close packing: finite, and the cross-level excess of a big
  // particle's box is negative (its own body holds no smaller centres).
  for (double alpha : {-1.0, -4.0, 0.0, 2.0}) {
    const PowerLaw d(alpha, 10);
    const double e = excess(d, 0.7, {5.0, 10.0, 20.0});
    EXPECT_TRUE(std::isfinite(e)) << alpha;
  }
  const PowerLaw mono(-3, 1.0001);
  EXPECT_TRUE(std::isfinite(excess(mono, 0.6, {2.0002})));
  // One radius exactly (a monodisperse file), 2D and 3D.
  const Empirical one(std::vector<double>(10, 0.5));
  for (int d : {2, 3}) {
    const ModelParams p{d, 0.3, 0.2, Search::top_down};
    EXPECT_LT(evaluate_excluded_model(one, p, {2.0}).T_cd_over_N, evaluate_model(one, p, {2.0}).T_cd_over_N) << d;
  }
}

TEST(ExcludedModel, RefusesWhatItCannotModel) {
  const PowerLaw d(-3, 10);
  EXPECT_THROW(evaluate_excluded_model(d, ModelParams{3, 1.0, 0.2, Search::top_down}, {20.0}), InputError);
  try {
    evaluate_excluded_model(PowerLaw(-3, 60), ModelParams{2, 0.3, 0.2, Search::top_down}, {120.0});
    ADD_FAILURE() << "2D, omega = 60 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "omega");
  }
  const PowerLaw wide(-3, 1e6);
  try {
    evaluate_excluded_model(wide, ModelParams{3, 0.5, 0.2, Search::top_down}, {2e6});
    ADD_FAILURE() << "omega = 1e6 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "omega");
  }
}

// The 2D solution's work budget (ExcludedOptions::disc_work_budget, `hgrid
// count --excluded-budget`): within it the answer is the unbudgeted one bit for
// bit; too small to try, refused before any iteration; run out, refused after.
TEST(ExcludedModel, DiscsWithinTheirWorkBudgetOrRefusedNamingIt) {
  const PowerLaw d(-3, 10);
  const std::vector<double> s = {4.0, 8.0, 20.0};
  const ModelParams p{2, 0.5, 0.2, Search::top_down};
  ExcludedOptions budget;
  budget.disc_work_budget = kDiscWorkPerSecond;
  EXPECT_EQ(evaluate_excluded_model(d, p, s, budget).T_over_N, evaluate_excluded_model(d, p, s).T_over_N);
  for (const double b : {1e6, 3e8}) {  // ~4e6 per iteration: 0 and 75 iterations of the ~110 it needs
    budget.disc_work_budget = b;
    try {
      evaluate_excluded_model(d, p, s, budget);
      ADD_FAILURE() << "a budget of " << b << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "excluded-budget");
      EXPECT_NE(std::string(e.what()).find(b < 1e7 ? "cannot be tried" : "did not converge within"), std::string::npos)
          << e.what();
    }
  }
}

TEST(PyNumeric, WorkBudgetRefusesBeforeIteratingOrWhenSpent) {
  const double eta = 0.6, rho = eta * 4 / std::numbers::pi;
  detail::PyNumericGrid g = fine_grid(16);
  g.max_work = 1.0;
  double per_iteration = 0;
  try {
    detail::PyNumeric(2, {rho}, {1.0}, g);
    ADD_FAILURE() << "one multiply-add accepted";
  } catch (const detail::PyWorkBudget& b) {
    EXPECT_TRUE(b.refused_before);
    EXPECT_EQ(b.affordable_iterations, 0);
    per_iteration = b.work_per_iteration;
  }
  g.max_work = 0;
  const int needed = detail::PyNumeric(2, {rho}, {1.0}, g).iterations();
  ASSERT_GT(needed, detail::kPyMinIterations);
  g.max_work = per_iteration * detail::kPyMinIterations;  // enough to try, too little to finish
  try {
    detail::PyNumeric(2, {rho}, {1.0}, g);
    ADD_FAILURE() << "finished in " << detail::kPyMinIterations << " iterations, needs " << needed;
  } catch (const detail::PyWorkBudget& b) {
    EXPECT_FALSE(b.refused_before);
    EXPECT_EQ(b.affordable_iterations, detail::kPyMinIterations);
  }
  g.max_work = per_iteration * needed;  // just enough
  EXPECT_EQ(detail::PyNumeric(2, {rho}, {1.0}, g).iterations(), needed);
}

TEST(ExcludedModel, WalledBoxesApproachTheBulk) {
  // The wall layer's share of the box falls like 1/A: so does the deviation.
  const PowerLaw d(-3, 10);
  const std::vector<double> s = {4.0, 8.0, 20.0};
  const ModelParams p{3, 0.4, 0.2, Search::top_down};
  const ModelResult bulk = evaluate_excluded_model(d, p, s);
  const auto deviation = [&](double A) {
    const ModelResult w = evaluate_excluded_model(d, p, s, {}, WallBox{{A, A, A}});
    EXPECT_LT(w.T_cd_over_N, bulk.T_cd_over_N) << A;  // fewer neighbours and fewer cells near a wall
    EXPECT_LT(w.T_ca_over_N, bulk.T_ca_over_N) << A;
    return std::abs(w.T_over_N / bulk.T_over_N - 1.0);
  };
  const double small = deviation(200.0), large = deviation(2000.0);
  EXPECT_LT(large, kWallBulkRelTol * 5);
  EXPECT_LT(large, small / 5);
}

TEST(ExcludedModel, WalledBoxesConvergeInTheWaveNumbers) {
  // The wall profiles' contact step is transformed in closed form and their
  // r-grid is fine: doubling k_max moves a small walled box (the Fig. 12
  // alpha = -3, N = 3000 one, where the wall layers weigh most) by < 1e-3.
  const PowerLaw d(-3, 10);
  const std::vector<double> s = {3.71, 6.29, 9.67, 14.14, 20.0};
  const ModelParams p{3, 0.6, 0.2, Search::top_down};
  const WallBox box{{72.5, 72.5, 72.5}};
  const ModelResult a = evaluate_excluded_model(d, p, s, {}, box);
  ExcludedOptions fine;
  fine.k_max *= 2;
  const ModelResult b = evaluate_excluded_model(d, p, s, fine, box);
  EXPECT_NEAR(b.T_over_N / a.T_over_N, 1.0, kDiscretisationRelTol);
}

TEST(ExcludedModel, WallLayerScansCountOnlyTheInterior) {
  // One cell spanning the box (s > A): every scan holds every centre, so the
  // share seen from outside the layer is the share of the scanning class's
  // positions in [layer, A - layer] out of its accessible [r, A - r].
  const double A = 100.0, r = 1.0, layer = 10.0;
  const detail::WallProfile a{r, 1.0, {}}, b{2.0, 1.0, {}};
  const detail::AxisScan ax = detail::scan_axis(A, a, 2.0 * A, false, 5.0, {b}, layer);
  EXPECT_NEAR(ax.fraction[0], 1.0, 1e-12);
  EXPECT_NEAR(ax.fraction_interior[0], (A - 2.0 * layer) / (A - 2.0 * r), 1e-3);
  EXPECT_NEAR(detail::scan_axis(A, a, 2.0 * A, false, 5.0, {b}).fraction_interior[0], 1.0, 1e-12);
}

TEST(ExcludedModel, DepletedWallLayerCarriesNoPairExcess) {
  // The Fig. 12 alpha = -3, N = 3000 box: sparing the wall layers the bulk
  // excess lowers the pair count, leaves the cell accesses, and matters less
  // in a larger box (the layers' share falls like 1/A).
  const PowerLaw d(-3, 10);
  const std::vector<double> s = {3.71, 6.29, 9.67, 14.14, 20.0};
  const ModelParams p{3, 0.6, 0.2, Search::top_down};
  ExcludedOptions product;
  product.wall_pairs = WallPairs::product;
  const auto gap = [&](double A) {
    const WallBox box{{A, A, A}};
    const ModelResult layer = evaluate_excluded_model(d, p, s, {}, box);
    const ModelResult prod = evaluate_excluded_model(d, p, s, product, box);
    EXPECT_LT(layer.T_cd_over_N, prod.T_cd_over_N) << A;
    EXPECT_EQ(layer.T_ca_over_N, prod.T_ca_over_N) << A;
    return prod.T_over_N / layer.T_over_N - 1.0;
  };
  const double small = gap(72.5), large = gap(725.0);
  EXPECT_GT(small, 0.02);  // ~4 % at N = 3000 (docs/MODEL.md section 8)
  EXPECT_LT(large, small / 5);
  // One radius: no larger class leaves a layer, the two agree.
  const PowerLaw mono(-3, 1.0);
  const std::vector<double> s1 = {4.0};
  const ModelParams p1{3, 0.4, 0.2, Search::top_down};
  const WallBox box{{40.0, 40.0, 40.0}};
  EXPECT_EQ(evaluate_excluded_model(mono, p1, s1, {}, box).T_over_N,
            evaluate_excluded_model(mono, p1, s1, product, box).T_over_N);
}

TEST(ExcludedModel, WallsMatchAnIndependentEvaluation) {
  // T/N in small walled cubes, the depleted wall layer and Kirkwood's product,
  // from a separate numpy evaluation (wall profiles by a direct sine sum on a
  // k grid twice as long, trapezoid-rule axis scans, k-space window
  // transforms): python3 tests/independent/walled_pins.py reproduces these.
  struct Case { double alpha, omega, nu; std::vector<double> sizes; double A, layer, product; };
  const std::vector<Case> cases = {{-3, 10, 0.4, {4, 8, 20}, 60.0, 13.120931, 13.480050},
                                   {-3, 10, 0.6, {3.71, 6.29, 9.67, 14.14, 20}, 72.5, 16.114029, 16.736928},
                                   {0, 10, 0.5, {5, 12, 20}, 80.0, 30.226097, 30.212257}};
  ExcludedOptions product;
  product.wall_pairs = WallPairs::product;
  for (const Case& c : cases) {
    const PowerLaw d(c.alpha, c.omega);
    const ModelParams p{3, c.nu, 0.2, Search::top_down};
    const WallBox box{{c.A, c.A, c.A}};
    EXPECT_NEAR(evaluate_excluded_model(d, p, c.sizes, {}, box).T_over_N / c.layer, 1.0, kIndependentWallRelTol)
        << "layer, alpha " << c.alpha << " nu " << c.nu;
    EXPECT_NEAR(evaluate_excluded_model(d, p, c.sizes, product, box).T_over_N / c.product, 1.0,
                kIndependentWallRelTol)
        << "product, alpha " << c.alpha << " nu " << c.nu;
  }
}

TEST(ExcludedModel, WalledSquaresApproachTheBulk) {
  // 2D: the wall layer's share of the square falls like 1/A.
  const PowerLaw d(-3, 5);
  const std::vector<double> s = {4.0, 10.0};
  const ModelParams p{2, 0.4, 0.2, Search::top_down};
  const ModelResult bulk = evaluate_excluded_model(d, p, s);
  const auto deviation = [&](double A) {
    const ModelResult w = evaluate_excluded_model(d, p, s, {}, WallBox{{A, A, 0.0}});
    EXPECT_LT(w.T_ca_over_N, bulk.T_ca_over_N) << A;  // fewer cells near a wall
    return std::abs(w.T_over_N / bulk.T_over_N - 1.0);
  };
  const double small = deviation(100.0), large = deviation(1000.0);
  EXPECT_LT(large, kWallBulkRelTol * 5);
  EXPECT_LT(large, small / 5);
}

}  // namespace
}  // namespace hgrid
