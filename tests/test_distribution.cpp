// Distributions: closed forms against quadrature, singular exponents, inverse
// CDF, empirical prefix sums, bad inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>

#include "hgridlab/model/distribution.hpp"
#include "hgridlab/base/error.hpp"

using namespace hgrid;

namespace {
constexpr double kQuadVsClosedRelTol = 1e-8;   // GSL QAGS (asked for 1e-12) vs closed form
constexpr double kSingularRelTol = 1e-8;        // alpha = -k-1 +- 1e-9 vs exactly -k-1
constexpr double kInverseAbsTol = 1e-10;        // cdf(quantile(u)) - u
constexpr double kExactRelTol = 1e-12;

const double kAlphas[] = {-6.0, -4.0, -3.5, -3.0, -2.0, -1.5, -1.0, -0.5, 0.0, 1.0, 2.5};
const double kOmegas[] = {1.0 + 1e-6, 1.5, 3.0, 100.0, 1e4, 1e6};

double rel(double a, double b) { return std::fabs(a - b) / std::max(std::fabs(b), 1e-300); }
}  // namespace

TEST(Distribution, PowerLawMomentsMatchQuadrature) {
  for (double alpha : kAlphas)
    for (double omega : kOmegas)
      for (int k = 0; k <= 4; ++k) {
        const PowerLaw f(alpha, omega);
        const double a = 1.0 + 0.1 * (omega - 1.0), b = 1.0 + 0.7 * (omega - 1.0);
        for (auto [lo, hi] : {std::pair{1.0, omega}, std::pair{a, b}}) {
          const double closed = f.moment(k, lo, hi), quad = f.moment_by_quadrature(k, lo, hi);
          EXPECT_LT(rel(closed, quad), kQuadVsClosedRelTol)
              << "alpha=" << alpha << " omega=" << omega << " k=" << k << " [" << lo << "," << hi << "]";
        }
      }
}

TEST(Distribution, PowerLawNormalisedAndCdfConsistent) {
  for (double alpha : kAlphas)
    for (double omega : kOmegas) {
      const PowerLaw f(alpha, omega, 2.5);
      EXPECT_NEAR(f.moment(0, 0.0, f.r_max()), 1.0, kExactRelTol);
      EXPECT_EQ(f.cdf(f.r_max()), 1.0);
      const double r = f.r_min() * std::sqrt(omega);
      EXPECT_NEAR(f.cdf(r), f.moment(0, 0.0, r), 1e-14);
    }
}

TEST(Distribution, PowerLawContinuousAcrossSingularExponents) {
  for (double omega : {1.0 + 1e-9, 2.0, 100.0, 1e6})
    for (int k = 0; k <= 3; ++k) {
      const double alpha = -k - 1.0;  // exponent alpha + k + 1 = 0: a logarithm
      const PowerLaw at(alpha, omega), below(alpha - 1e-9, omega), above(alpha + 1e-9, omega);
      const double m = at.moment(k, 1.0, omega);
      EXPECT_LT(rel(below.moment(k, 1.0, omega), m), kSingularRelTol) << omega << " " << k;
      EXPECT_LT(rel(above.moment(k, 1.0, omega), m), kSingularRelTol) << omega << " " << k;
    }
}

TEST(Distribution, PowerLawNearlyMonodisperseIsADelta) {
  const PowerLaw f(-3.0, 1.0 + 1e-9, 2.0), delta(-3.0, 1.0, 2.0);
  for (int k = 0; k <= 3; ++k) {
    EXPECT_LT(rel(f.moment(k, 0.0, 10.0), std::pow(2.0, k)), 1e-8);
    EXPECT_DOUBLE_EQ(delta.moment(k, 0.0, 10.0), std::pow(2.0, k));
    EXPECT_EQ(delta.moment(k, 2.0, 10.0), 0.0);  // (a, b] excludes a
  }
}

TEST(Distribution, QuantileInvertsCdf) {
  for (double alpha : kAlphas)
    for (double omega : kOmegas) {
      const PowerLaw f(alpha, omega);
      for (double u : {0.0, 1e-6, 0.1, 0.5, 0.9, 0.999999, 1.0}) {
        // cdf is ill-conditioned where r f(r) is large (omega -> 1): allow its rounding.
        const double r = f.quantile(u), cond = 8 * std::numeric_limits<double>::epsilon() * r * f.pdf(r);
        EXPECT_NEAR(f.cdf(r), u, kInverseAbsTol + cond) << alpha << " " << omega << " " << u;
      }
    }
  const LogNormal g = LogNormal::centred(0.8, 50.0);
  for (double u : {0.0, 0.01, 0.5, 0.99, 1.0}) EXPECT_NEAR(g.cdf(g.quantile(u)), u, kInverseAbsTol);
}

TEST(Distribution, SampleMeanMatchesMoment) {
  const PowerLaw f(-2.0, 10.0);
  const auto r = f.sample(200000, 42);
  const double mean = std::accumulate(r.begin(), r.end(), 0.0) / static_cast<double>(r.size());
  const double m1 = f.moment(1, 1.0, 10.0), var = f.moment(2, 1.0, 10.0) - m1 * m1;
  EXPECT_NEAR(mean, m1, 5.0 * std::sqrt(var / static_cast<double>(r.size())));  // 5 sigma
  for (double x : r) ASSERT_TRUE(x >= 1.0 && x <= 10.0);
}

TEST(Distribution, LogNormalMomentsMatchQuadrature) {
  for (double sigma : {0.1, 0.5, 1.0, 3.0})
    for (double omega : {1.5, 10.0, 1e3, 1e6})
      for (int k = 0; k <= 3; ++k) {
        const LogNormal g = LogNormal::centred(sigma, omega, 0.3);
        const double lo = g.r_min(), hi = g.r_max(), mid = std::sqrt(lo * hi);
        EXPECT_LT(rel(g.moment(k, lo, hi), g.moment_by_quadrature(k, lo, hi)), kQuadVsClosedRelTol);
        EXPECT_LT(rel(g.moment(k, mid, hi), g.moment_by_quadrature(k, mid, hi)), kQuadVsClosedRelTol);
      }
  EXPECT_NEAR(LogNormal::centred(1.0, 100.0).moment(0, 0.0, 1e9), 1.0, kExactRelTol);
}

TEST(Distribution, EmpiricalPrefixSumsMatchDirectSums) {
  const std::vector<double> radii{3.0, 1.0, 2.0, 2.0, 5.0, 1.5};
  const Empirical e(radii);
  EXPECT_EQ(e.r_min(), 1.0);
  EXPECT_EQ(e.r_max(), 5.0);
  for (double k : {0.0, 1.0, 2.0, 3.0, 2.5})
    for (auto [a, b] : {std::pair{0.0, 10.0}, std::pair{1.5, 3.0}, std::pair{2.0, 2.0}, std::pair{1.0, 2.0}}) {
      double direct = 0;
      for (double r : radii)
        if (r > a && r <= b) direct += std::pow(r, k);
      EXPECT_NEAR(e.moment(k, a, b), direct / 6.0, 1e-14) << k << " " << a << " " << b;
    }
  EXPECT_DOUBLE_EQ(e.cdf(2.0), 4.0 / 6.0);
  EXPECT_EQ(e.quantile(0.0), 1.0);
  EXPECT_EQ(e.quantile(0.5), 2.0);
  EXPECT_EQ(e.quantile(1.0), 5.0);
}

// moments() (the cost model's batch) returns moment()'s values exactly, for
// the Empirical override (radii found once) and the default loop alike,
// including empty intervals and an order beyond the prefix sums.
TEST(Distribution, MomentsBatchEqualsMomentExactly) {
  const Empirical e(PowerLaw(-3.0, 10.0).sample(1000, 7));
  const PowerLaw pl(-2.0, 5.0);
  for (auto [a, b] : {std::pair{0.0, 100.0}, std::pair{1.2, 3.7}, std::pair{2.0, 2.0}, std::pair{4.0, 1.0},
                      std::pair{0.0, e.r_min()}, std::pair{e.r_max(), 200.0}})
    for (int kmax : {0, 3, 5}) {
      double out[6];
      e.moments(kmax, a, b, out);
      for (int k = 0; k <= kmax; ++k) EXPECT_EQ(out[k], e.moment(k, a, b)) << "empirical " << k << " " << a << " " << b;
      pl.moments(kmax, a, b, out);
      for (int k = 0; k <= kmax; ++k) EXPECT_EQ(out[k], pl.moment(k, a, b)) << "power law " << k << " " << a << " " << b;
    }
}

TEST(Distribution, EmpiricalOfASampleApproachesTheLaw) {
  const PowerLaw f(-3.0, 100.0);
  const Empirical e(f.sample(400000, 7));
  for (int k = 0; k <= 3; ++k) EXPECT_LT(rel(e.moment(k, 0.0, 20.0), f.moment(k, 0.0, 20.0)), 0.05);
}

TEST(Distribution, BadInputsRejected) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(PowerLaw(-3.0, 0.5), InputError);
  EXPECT_THROW(PowerLaw(nan, 10.0), InputError);
  EXPECT_THROW(PowerLaw(-3.0, nan), InputError);
  EXPECT_THROW(PowerLaw(-3.0, 10.0, 0.0), InputError);
  EXPECT_THROW(LogNormal::centred(0.0, 10.0), InputError);
  EXPECT_THROW(LogNormal::centred(1.0, 1.0), InputError);
  EXPECT_THROW(Empirical({}), InputError);
  EXPECT_THROW(Empirical({1.0, -2.0}), InputError);
  EXPECT_THROW(Empirical({1.0, nan}), InputError);
  try {
    PowerLaw(-3.0, 0.5);
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "omega");
    EXPECT_NE(std::string(e.what()).find(">= 1"), std::string::npos) << e.what();
  }
}
