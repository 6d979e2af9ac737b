// PairSum: sums over pairs in canonical order on 1, 2, 3 and 8 threads equal
// one thread's sums bit for bit, for pair lists split among the threads in
// any way, skewed towards a few particles, or empty; a callback's exception
// reaches the caller.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "hgridlab/contacts/pair_sum.hpp"

namespace hgrid {
namespace {

constexpr std::uint64_t kPairSumSeed = 4099;

struct Contribution {
  double a, b;
};

// Per-particle sums of contributions that do not commute in floating point
// (a particle's result depends on the order of its additions).
std::vector<double> sums(PairSum& ps, std::size_t n) {
  std::vector<double> acc(n), out(n);
  std::vector<Contribution> scratch;
  ps.sum(
      scratch,
      [](std::uint32_t i, std::uint32_t j) {
        return Contribution{std::sin(1e-3 * i + 0.7 * j) * 1e8, std::cos(0.3 * i - 1e-2 * j) * 1e-8};
      },
      [&](std::size_t p) { acc[p] = 1.0 / (1.0 + static_cast<double>(p)); },
      [&](const Contribution& c, std::size_t i) { acc[i] = acc[i] * 0.999 + c.a; },
      [&](const Contribution& c, std::size_t j) { acc[j] = acc[j] * 1.001 - c.b; },
      [&](std::size_t p) { out[p] = acc[p]; });
  return out;
}

// Reference: one loop over the pairs in (i, j) order.
std::vector<double> reference(const std::set<std::pair<std::uint32_t, std::uint32_t>>& pairs, std::size_t n) {
  std::vector<double> acc(n);
  for (std::size_t p = 0; p < n; ++p) acc[p] = 1.0 / (1.0 + static_cast<double>(p));
  for (const auto& [i, j] : pairs) {
    const Contribution c{std::sin(1e-3 * i + 0.7 * j) * 1e8, std::cos(0.3 * i - 1e-2 * j) * 1e-8};
    acc[i] = acc[i] * 0.999 + c.a;
    acc[j] = acc[j] * 1.001 - c.b;
  }
  return acc;
}

void check(std::size_t n, const std::set<std::pair<std::uint32_t, std::uint32_t>>& pairs, std::uint64_t seed) {
  const auto want = reference(pairs, n);
  std::mt19937_64 rng(seed);
  for (int threads : {1, 2, 3, 8}) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", n " + std::to_string(n) + ", threads " + std::to_string(threads));
    PairSum ps(n);
    std::vector<std::vector<std::uint64_t>> lists(static_cast<std::size_t>(threads));
    std::uniform_int_distribution<int> pick(0, threads - 1);
    for (const auto& [i, j] : pairs) lists[static_cast<std::size_t>(pick(rng))].push_back(ps.key(i, j));
    for (int round = 0; round < 2; ++round) {  // scratch reused
      ps.gather(lists);
      ASSERT_EQ(ps.keys().size(), pairs.size());
      EXPECT_TRUE(std::is_sorted(ps.keys().begin(), ps.keys().end()));
      EXPECT_TRUE(sums(ps, n) == want);
    }
  }
}

TEST(PairSum, SameAsOneLoopForAnyThreads) {
  std::mt19937_64 rng(kPairSumSeed);
  for (std::size_t n : {1u, 2u, 7u, 1000u, 50000u}) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
    std::uniform_int_distribution<std::uint32_t> u(0, static_cast<std::uint32_t>(n - 1));
    for (std::size_t k = 0; k < 3 * n; ++k) {
      const std::uint32_t a = u(rng), b = u(rng);
      if (a != b) pairs.emplace(std::min(a, b), std::max(a, b));
    }
    check(n, pairs, kPairSumSeed + n);
  }
}

TEST(PairSum, SkewedAndEmpty) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> star, none;
  for (std::uint32_t j = 1; j < 5000; ++j) star.emplace(0, j);  // one particle in every pair
  check(5000, star, kPairSumSeed + 1);
  std::set<std::pair<std::uint32_t, std::uint32_t>> tail;
  for (std::uint32_t i = 4990; i < 5000; ++i)
    for (std::uint32_t j = i + 1; j < 5000; ++j) tail.emplace(i, j);  // all pairs among the last particles
  check(5000, tail, kPairSumSeed + 2);
  check(5000, none, kPairSumSeed + 3);
}

TEST(PairSum, ExceptionReachesTheCaller) {
  for (int threads : {1, 2, 8}) {
    PairSum ps(100);
    std::vector<std::vector<std::uint64_t>> lists(static_cast<std::size_t>(threads));
    for (std::uint32_t i = 0; i + 1 < 100; ++i) lists[i % lists.size()].push_back(ps.key(i, i + 1));
    ps.gather(lists);
    std::vector<Contribution> scratch;
    auto nothing = [](const Contribution&, std::size_t) {};
    EXPECT_THROW(ps.sum(
                     scratch,
                     [](std::uint32_t i, std::uint32_t) {
                       if (i == 50) throw std::runtime_error("pair");
                       return Contribution{};
                     },
                     [](std::size_t) {}, nothing, nothing, [](std::size_t) {}),
                 std::runtime_error);
    EXPECT_THROW(ps.sum(
                     scratch, [](std::uint32_t, std::uint32_t) { return Contribution{}; }, [](std::size_t) {}, nothing,
                     nothing,
                     [](std::size_t p) {
                       if (p == 70) throw std::runtime_error("particle");
                     }),
                 std::runtime_error);
  }
}

}  // namespace
}  // namespace hgrid
