// Event-chain Monte Carlo (packing/detail/gen_event_chain.hpp): the
// distribution it samples on a system whose distribution is known exactly,
// and the packings it equilibrates (no overlap beyond its shrink, nu and
// radii kept, resumable bit for bit, walls refused).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <unistd.h>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/packing/detail/gen_event_chain.hpp"
#include "hgridlab/packing/generate.hpp"
#include "hgridlab/packing/identity.hpp"

#include "killed_run.hpp"

namespace hgrid {
namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kEventChainSeed = 20261129;
/// Sweeps sampled in the two-sphere tests (one sample per sweep: a chain
/// there moves the pair through 20 radii, twice the box side), and the
/// largest difference of a sampled probability from the exact one: 4.5
/// standard errors of a proportion near 1/2 over independent samples.
constexpr int kSamples = 40000;
constexpr double kBalanceTol = 4.5 * 0.5 / 200.0;  // 4.5 sqrt(1/4 / kSamples)

/// Two spheres of radii ra, rb in a periodic box of side L: every separation
/// r outside contact (|r| >= sigma, the shrunk contact distance) is equally
/// likely, so P(|r| < R) = (V(R) - V(sigma)) / (L^d - V(sigma)) for R <= L/2,
/// V the volume of a d-ball. The chains lift from one sphere to the other
/// and back; the pair never comes closer than sigma.
template <int D>
void two_spheres_sample_the_uniform_distribution(double ra, double rb, double L) {
  SCOPED_TRACE("d " + std::to_string(D) + " seed " + std::to_string(kEventChainSeed));
  Extent<D> box;
  box.fill(L);
  const std::vector<double> radii{ra, rb};
  std::vector<double> pos(2 * D, 0.5 * L);
  pos[0] = 0.1 * L;
  detail::EventChain<D> chains(box, radii, pos);
  detail::GenRng rng(kEventChainSeed);
  const double sigma = (ra + rb) * (1 - detail::kChainShrink);
  const auto ball = [](double r) { return D == 3 ? 4.0 / 3.0 * std::numbers::pi * r * r * r : std::numbers::pi * r * r; };
  const double room = 0.5 * L - sigma;
  const std::array<double, 4> reach{sigma + 0.25 * room, sigma + 0.5 * room, sigma + 0.75 * room, 0.5 * L};
  std::array<int, 4> inside{};
  double closest = L;
  for (int m = 0; m < kSamples; ++m) {
    chains.sweep(rng);
    double r2 = 0;
    for (int k = 0; k < D; ++k) {
      const double dx = detail::min_image(pos[D + k] - pos[k], L);
      r2 += dx * dx;
    }
    const double r = std::sqrt(r2);
    closest = std::min(closest, r);
    for (std::size_t b = 0; b < reach.size(); ++b) inside[b] += r < reach[b];
  }
  EXPECT_GE(closest, sigma);
  const double free = std::pow(L, D) - ball(sigma);
  for (std::size_t b = 0; b < reach.size(); ++b)
    EXPECT_NEAR(inside[b] / static_cast<double>(kSamples), (ball(reach[b]) - ball(sigma)) / free, kBalanceTol)
        << "|r| < " << reach[b];
}

TEST(EventChain, TwoSpheresSampleTheUniformDistribution) { two_spheres_sample_the_uniform_distribution<3>(1, 2, 10); }
TEST(EventChain, TwoDiscsSampleTheUniformDistribution) { two_spheres_sample_the_uniform_distribution<2>(1, 1.5, 8); }
// A box barely wider than 4 r_max (5 radii; an event looks one radius
// ahead): the sphere ahead may lie over half a box away, and must still be
// met going forward.
TEST(EventChain, TwoSpheresInANarrowBox) { two_spheres_sample_the_uniform_distribution<3>(1, 1, 5); }

PackingSpec chain_spec(int d, double nu, ExcludedMethod method) {
  PackingSpec s;
  s.d = d;
  s.n = d == 3 ? 1500 : 1000;
  s.nu = nu;
  s.alpha = -3;
  s.omega = 10;
  s.placement = Placement::excluded;
  s.method = method;
  s.seed = kEventChainSeed;
  s.progress = false;
  s.equilibrate = true;
  s.moves = EquilibrationMoves::event_chain;
  s.sweeps = 20;
  return s;
}

// From sequential addition (no overlap) and from compression (overlaps up
// to 1e-4): radii and nu kept, pairs overlapping by at most the chains'
// shrink, the positions moved; the number of threads changes nothing.
// The insertion grid's two box visits (visit_box, one list at a time;
// visit_box_all, heads fetched a batch ahead) meet the same spheres, each
// once, for boxes from a fraction of a cell to wider than the box.
TEST(EventChain, BatchedBoxVisitMeetsTheSameSpheres) {
  constexpr std::uint64_t kSeed = 7;
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> u(0, 1);
  const Extent<3> box{40, 30, 50};
  std::vector<double> radii(3000);
  for (double& r : radii) r = 1 + 9 * std::pow(u(rng), 4);
  detail::InsertGrid<3, Boundary::periodic> grid(box, radii);
  for (std::uint32_t i = 0; i < radii.size(); ++i) grid.insert(i, {u(rng) * 40, u(rng) * 30, u(rng) * 50}, radii[i]);
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial) + " seed " + std::to_string(kSeed));
    const std::array<double, 3> x{u(rng) * 40, u(rng) * 30, u(rng) * 50};
    std::array<double, 3> lo, hi;
    for (int k = 0; k < 3; ++k) {
      lo[k] = -u(rng) * (trial % 10 == 0 ? 40 : 8);
      hi[k] = u(rng) * 8;
    }
    for (int l = 0; l < grid.levels(); ++l) {
      std::vector<std::uint32_t> one, all;
      grid.visit_box(l, x, lo, hi, [&](std::uint32_t q, const std::array<double, 3>&, double) {
        one.push_back(q);
        return true;
      });
      grid.visit_box_all(l, x, lo, hi, [&](std::uint32_t q, const std::array<double, 3>&, double) { all.push_back(q); });
      std::sort(one.begin(), one.end());
      std::sort(all.begin(), all.end());
      EXPECT_EQ(one, all) << "level " << l;
      EXPECT_EQ(std::adjacent_find(all.begin(), all.end()), all.end()) << "level " << l;
    }
  }
}

TEST(EventChain, EquilibratesPackingsWithinItsShrink) {
  for (const auto& [d, nu, method] : std::vector<std::tuple<int, double, ExcludedMethod>>{
           {3, 0.5, ExcludedMethod::rsa}, {3, 0.6, ExcludedMethod::growth}, {2, 0.7, ExcludedMethod::growth}}) {
    SCOPED_TRACE("d " + std::to_string(d) + " nu " + std::to_string(nu) + " " + to_string(method) + " seed " +
                 std::to_string(kEventChainSeed));
    auto s = chain_spec(d, nu, method);
    s.equilibrate = false;
    s.moves = EquilibrationMoves::metropolis;
    const Packing placed = generate_packing(s);
    s.equilibrate = true;
    s.moves = EquilibrationMoves::event_chain;
    s.threads = 1;
    const Packing after = generate_packing(s, &placed);
    EXPECT_EQ(after.radii, placed.radii);
    EXPECT_NE(after.positions, placed.positions);
    EXPECT_NEAR(after.packing_fraction() / nu, 1.0, 1e-12);
    EXPECT_LE(assess_packing(after, nullptr).max_rel_overlap, detail::kChainShrink);
    EXPECT_GT(after.num_attrs.at("equilibration_swap_acceptance"), 0.0);
    EXPECT_EQ(after.str_attrs.at("equilibration_moves"), "event-chain");
    s.threads = 2;
    EXPECT_EQ(generate_packing(s, &placed).positions, after.positions);
  }
}

// Resumed from a finished stage (through a file) and from a checkpoint of a
// run killed part-way: the uninterrupted run's packing, bit for bit.
TEST(EventChain, ResumedIsTheUninterruptedOne) {
  const fs::path dir = fs::temp_directory_path() / ("hgrid_event_chain_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  auto s = chain_spec(3, 0.55, ExcludedMethod::growth);
  const Packing whole = generate_packing(s);
  auto s8 = s;
  s8.sweeps = 8;
  write_packing((dir / "s8.h5").string(), generate_packing(s8));
  const Packing stage = read_packing((dir / "s8.h5").string());
  EXPECT_EQ(resume_mismatch(stage, s), "");
  EXPECT_EQ(generate_packing(s, &stage).positions, whole.positions);
  const std::vector<Packing> checkpoints = test::checkpoints_until_killed(s, 13);
  ASSERT_EQ(checkpoints.size(), 13u);
  const Packing resumed = generate_packing(s, &checkpoints.back());
  EXPECT_EQ(resumed.positions, whole.positions);
  EXPECT_EQ(resumed.str_attrs.at("equilibration_rng_state"), whole.str_attrs.at("equilibration_rng_state"));
  // A Metropolis stage is another chain: not resumed as this one.
  auto m = s8;
  m.moves = EquilibrationMoves::metropolis;
  EXPECT_NE(resume_mismatch(generate_packing(m), s), "");
  fs::remove_all(dir);
}

TEST(EventChain, RefusesWallsAndUnknownMoves) {
  auto s = chain_spec(3, 0.4, ExcludedMethod::rsa);
  s.boundary = Boundary::walls;
  try {
    generate_packing(s);
    ADD_FAILURE() << "event chains need a periodic box";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("moves"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_equilibration_moves("kinetic"), InputError);
  EXPECT_EQ(parse_equilibration_moves("event-chain"), EquilibrationMoves::event_chain);
  s.boundary = Boundary::periodic;
  s.equilibrate = false;
  EXPECT_THROW(generate_packing(s), InputError);  // moves without an equilibration
}

}  // namespace
}  // namespace hgrid
