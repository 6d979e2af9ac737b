// The load-balance simulation (measure/balance.hpp): the dynamic
// schedule's makespan on hand-made costs, and the simulation on a packing.
#include <gtest/gtest.h>

#include <vector>

#include "hgridlab/measure/balance.hpp"
#include "support.hpp"

namespace {

using namespace hgrid;
using namespace hgrid::test;

TEST(Balance, MakespanOfTheDynamicSchedule) {
  const std::vector<double> even{3, 3, 3, 3};
  EXPECT_DOUBLE_EQ(simulated_makespan(even, 2), 6);
  EXPECT_DOUBLE_EQ(simulated_makespan(even, 4), 3);
  EXPECT_DOUBLE_EQ(simulated_makespan(even, 8), 3);  // more threads than pieces
  const std::vector<double> one_big{10, 1, 1};
  EXPECT_DOUBLE_EQ(simulated_makespan(one_big, 2), 10);
  const std::vector<double> late_big{1, 1, 10};  // handed out last: waits for a free thread
  EXPECT_DOUBLE_EQ(simulated_makespan(late_big, 2), 11);
  EXPECT_THROW(simulated_makespan(even, 0), InputError);
}

TEST(Balance, OnAPacking) {
  const Scene<3> s = random_scene<3>(20000, 0.5, -3.0, 20.0, Boundary::periodic, 21);  // seed 21
  const Packing p = packing_from(s, Boundary::periodic);
  const std::vector<int> threads{1, 2, 8};
  const auto b = simulate_balance(p, GridParams{exponential_sizes(4, 1.0, 20.0)}, threads, BalanceCost{});
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0].threads, 1);
  EXPECT_NEAR(b[0].imbalance, 0.0, 1e-12);  // one thread does all the work
  for (const auto& r : b) {
    EXPECT_GE(r.imbalance, -1e-12);
    EXPECT_GT(r.pieces, 0u);
  }
  EXPECT_LT(b[1].imbalance, 0.2);  // 2 threads, many pieces
}

}  // namespace
