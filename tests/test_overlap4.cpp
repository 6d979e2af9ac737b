// The four-wide overlap test (grid/detail/overlap4.hpp) gives, lane by lane,
// the scalar test's answer (geometry.hpp): on random spheres, on pairs that
// touch exactly (integer coordinates: the distance equals the sum of radii,
// not an overlap), and across the periodic box's half-width.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "hgridlab/grid/detail/overlap4.hpp"

namespace hgrid::test {
namespace {

template <int D, Boundary B>
void compare(std::uint64_t seed, bool lattice) {
  std::mt19937_64 rng(seed);
  const Extent<D> box = [] {
    Extent<D> e{};
    for (int k = 0; k < D; ++k) e[k] = 10.0 + k;  // a side of 10 or 11
    return e;
  }();
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> cell(0, 9), rad(1, 3);
  auto sphere = [&] {
    Sphere<D> s{};
    for (int k = 0; k < D; ++k) s.x[k] = lattice ? cell(rng) : box[k] * u(rng);
    s.r = lattice ? 0.5 * rad(rng) : 0.05 + 3.0 * u(rng);
    return s;
  };
  std::vector<Sphere<D>> s(4);
  std::uint64_t hits = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Sphere<D> p = sphere();
    for (auto& q : s) q = sphere();
    const unsigned bits = detail::overlap4<D, B>(p, s.data(), box);
    for (unsigned t = 0; t < 4; ++t) {
      const bool scalar = detail::overlap<D, B>(p, s[t], box);
      hits += scalar;
      ASSERT_EQ(((bits >> t) & 1u) != 0, scalar)
          << "seed=" << seed << " trial=" << trial << " lane=" << t << " d=" << D << " " << to_string(B);
    }
  }
  EXPECT_GT(hits, 0u);  // both answers were exercised
}

TEST(Overlap4, MatchesScalarTest) {
  for (bool lattice : {false, true}) {
    compare<2, Boundary::walls>(11, lattice);
    compare<2, Boundary::periodic>(12, lattice);
    compare<3, Boundary::walls>(13, lattice);
    compare<3, Boundary::periodic>(14, lattice);
  }
}

}  // namespace
}  // namespace hgrid::test
