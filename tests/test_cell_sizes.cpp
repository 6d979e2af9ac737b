// Cell-size methods and L*: paper statements, the optimum's dominance and
// robustness, constant-ratio property, empirical input, bad inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/model/detail/model_sizes.hpp"
#include "hgridlab/base/error.hpp"

using namespace hgrid;

namespace {
constexpr double kDominanceRelTol = 1e-9;   // optimum may tie another method to rounding
constexpr double kRobustRelTol = 1e-7;      // optimum from random starts
constexpr double kRatioRelTol = 1e-9;       // m_{h+1} / m_h = q
constexpr double kPaperAbsTol = 0.05;       // docs/MODEL.md section 3 values

const CellMethod kMethods[] = {CellMethod::linear, CellMethod::exponential, CellMethod::constant,
                               CellMethod::optimal};

void expect_valid(const Distribution& f, const std::vector<double>& s) {
  ASSERT_FALSE(s.empty());
  EXPECT_GE(s.front(), 2.0 * f.r_min() * (1 - 1e-12));
  EXPECT_DOUBLE_EQ(s.back(), 2.0 * f.r_max());
  for (std::size_t h = 1; h < s.size(); ++h) EXPECT_LE(s[h - 1], s[h]);
}
ModelParams bottom_up() {
  ModelParams p;
  p.search = Search::bottom_up;
  return p;
}
}  // namespace

TEST(CellSize, EveryMethodGivesValidSizes) {
  for (double alpha : {-3.0, 0.0})
    for (double omega : {1.0, 1.0 + 1e-9, 3.0, 100.0, 1e6})
      for (CellMethod m : kMethods)
        for (int L : {1, 2, 5}) {
          const PowerLaw f(alpha, omega);
          expect_valid(f, cell_sizes(f, ModelParams{}, m, L));
        }
}

TEST(CellSize, ConstantRatioHoldsEveryLevel) {
  const PowerLaw f(-3.0, 100.0);
  for (double q : {0.5, 1.0, 2.0, 5.0}) {
    const auto c = choose_cell_sizes(f, ModelParams{}, CellMethod::constant, 8, q);
    for (int h = 1; h < 8; ++h) EXPECT_NEAR(c.model.m[h] / c.model.m[h - 1], q, kRatioRelTol * q) << q << " " << h;
  }
}

TEST(CellSize, PaperValuesUniformOmega100) {
  // docs/MODEL.md section 3: q = 1, Top-Down, at its best L: about 29.5 (from 74.3).
  const auto c = choose_cell_sizes(PowerLaw(0.0, 100.0), ModelParams{}, CellMethod::constant);
  EXPECT_NEAR(c.model.T_over_N, 29.5, kPaperAbsTol) << "L* = " << c.levels;
}

TEST(CellSize, PaperLevelsUniformVolumeOmega100) {
  const PowerLaw f(-3.0, 100.0);
  EXPECT_EQ(choose_cell_sizes(f, ModelParams{}, CellMethod::linear).levels, 43);  // Sect. 5.3
  EXPECT_EQ(choose_cell_sizes(f, ModelParams{}, CellMethod::exponential).levels, 4);
  const int Lq = choose_cell_sizes(f, ModelParams{}, CellMethod::constant).levels;
  EXPECT_GE(Lq, 10);  // "best near L = 12"
  EXPECT_LE(Lq, 14);
}

TEST(CellSize, OptimumNeverAboveAnyOtherMethod) {
  for (const ModelParams& p : {ModelParams{}, bottom_up()})
    for (double alpha : {-3.0, 0.0})
      for (double omega : {2.0, 100.0, 1000.0}) {
        const PowerLaw f(alpha, omega);
        const double best = choose_cell_sizes(f, p, CellMethod::optimal).model.T_over_N;
        for (CellMethod m : kMethods) {
          const auto other = choose_cell_sizes(f, p, m);
          EXPECT_LE(best, other.model.T_over_N * (1 + kDominanceRelTol))
              << to_string(m) << " alpha=" << alpha << " omega=" << omega << " " << to_string(p.search);
          const double at_L = choose_cell_sizes(f, p, CellMethod::optimal, other.levels).model.T_over_N;
          EXPECT_LE(at_L, other.model.T_over_N * (1 + kDominanceRelTol))
              << to_string(m) << " L=" << other.levels << " rel " << at_L / other.model.T_over_N - 1 << " alpha="
              << alpha << " omega=" << omega << " " << to_string(p.search);
        }
      }
}

TEST(CellSize, OptimumRobustToStartingPoints) {
  // Top-Down: Newton reaches the same optimum from any random start. Bottom-Up
  // has genuine local minima (empty bottom levels), so there the claim is that
  // no random start finds anything better than the answer of cell_sizes().
  const PowerLaw f(-3.0, 100.0);
  for (const ModelParams& p : {ModelParams{}, bottom_up()}) {
    const detail::CostModel cm(f, p);
    const int L = 6;
    const double ref = cm.total(cell_sizes(f, p, CellMethod::optimal, L));
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<double> s(L);
      for (auto& v : s) v = 2.0 * std::pow(100.0, u(rng));
      std::sort(s.begin(), s.end());
      s.back() = 200.0;
      const double T = cm.total(detail::optimise_sizes(cm, L, {s}));
      EXPECT_GE(T, ref * (1 - kRobustRelTol)) << "trial " << trial;
      if (p.search == Search::top_down) {
        EXPECT_LT((T - ref) / ref, kRobustRelTol) << "trial " << trial;
      }
    }
  }
}

TEST(CellSize, OptimalLevelsAreTheSmallestOnTheFlat) {
  const PowerLaw f(-3.0, 100.0);
  const auto c = choose_cell_sizes(f, ModelParams{}, CellMethod::optimal);
  const auto T = cost_versus_levels(f, ModelParams{}, CellMethod::optimal, c.levels + 4);
  const double tmin = *std::min_element(T.begin(), T.end());
  EXPECT_LE(c.model.T_over_N, tmin * (1 + kLevelsFlatRelTol));
  for (int L = 1; L < c.levels; ++L) EXPECT_GT(T[L - 1], tmin * (1 + kLevelsFlatRelTol)) << L;
  for (std::size_t L = 1; L < T.size(); ++L) EXPECT_LE(T[L], T[L - 1] * (1 + 1e-12));  // non-increasing
}

TEST(CellSize, InvariantToLengthUnit) {
  const double unit = 0.013;
  for (CellMethod m : kMethods) {
    const auto a = choose_cell_sizes(PowerLaw(-3.0, 100.0), ModelParams{}, m);
    const auto b = choose_cell_sizes(PowerLaw(-3.0, 100.0, unit), ModelParams{}, m);
    EXPECT_EQ(a.levels, b.levels) << to_string(m);
    EXPECT_NEAR(a.model.T_over_N, b.model.T_over_N, 1e-7 * a.model.T_over_N) << to_string(m);
  }
}

TEST(CellSize, EmpiricalRadiiWork) {
  const PowerLaw f(-3.0, 100.0);
  const Empirical e(f.sample(200000, 11));
  ModelParams p;
  const double law = choose_cell_sizes(f, p, CellMethod::optimal).model.T_over_N;
  const auto c = choose_cell_sizes(e, p, CellMethod::optimal);
  expect_valid(e, c.sizes);
  EXPECT_NEAR(c.model.T_over_N, law, 0.02 * law);
  for (CellMethod m : kMethods) {
    const auto o = choose_cell_sizes(e, p, m);
    expect_valid(e, o.sizes);
    EXPECT_LE(c.model.T_over_N, o.model.T_over_N * (1 + kDominanceRelTol)) << to_string(m);
  }
  // A bidisperse list: the step CDF must not trouble the optimiser.
  std::vector<double> bi(1000, 1.0);
  bi.insert(bi.end(), 10, 10.0);
  const Empirical b(bi);
  const auto cb = choose_cell_sizes(b, p, CellMethod::optimal);
  expect_valid(b, cb.sizes);
  EXPECT_LE(cb.model.T_over_N, choose_cell_sizes(b, p, CellMethod::exponential).model.T_over_N);
  EXPECT_EQ(cb.levels, 2);
}

TEST(CellSize, BadInputsRejected) {
  const PowerLaw f(-3.0, 10.0);
  EXPECT_THROW(parse_cell_method("quadratic"), InputError);
  EXPECT_EQ(parse_cell_method("optimal"), CellMethod::optimal);
  EXPECT_THROW(choose_cell_sizes(f, ModelParams{}, CellMethod::linear, 0), InputError);
  EXPECT_THROW(choose_cell_sizes(f, ModelParams{}, CellMethod::constant, 3, 0.0), InputError);
  EXPECT_THROW(choose_cell_sizes(f, ModelParams{}, CellMethod::constant, 3, -1.0), InputError);
  EXPECT_THROW(choose_cell_sizes(f, ModelParams{}, CellMethod::constant, 3, std::nan("")), InputError);
  try {
    parse_cell_method("quadratic");
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "cells");
  }
}
