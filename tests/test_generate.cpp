// Packing generators: radius sample vs pdf, exact nu, overlaps, walls,
// reproducibility, the cache, rcp estimates and rejected arguments.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include <random>

#include "hgridlab/contacts/contact_list.hpp"
#include "hgridlab/packing/detail/gen_pairs.hpp"
#include "hgridlab/packing/detail/gen_relax.hpp"
#include "hgridlab/base/progress.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/packing/generate.hpp"
#include "hgridlab/packing/rcp.hpp"
#include "support.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/io/packing_cache.hpp"

#include "killed_run.hpp"

namespace hgrid {
namespace {

namespace fs = std::filesystem;

using test::kNuTol;
constexpr double kMinKsPvalue = 1e-3;      // goodness of fit of the radius sample
constexpr double kRelaxedOverlapTol = 1e-4;  // growth + FIRE packings
constexpr std::uint64_t kGenerateSeed = 20140901;

PackingSpec spec(int d, std::size_t n, double nu, double alpha, double omega, Placement pl,
                 Boundary b = Boundary::periodic, std::uint64_t seed = kGenerateSeed) {
  PackingSpec s;
  s.d = d;
  s.n = n;
  s.nu = nu;
  s.alpha = alpha;
  s.omega = omega;
  s.placement = pl;
  s.boundary = b;
  s.seed = seed;
  s.progress = false;
  return s;
}

fs::path temp_dir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("hgrid_gen_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

TEST(Generate, RadiusSampleFitsPdf) {
  for (auto [alpha, omega] : std::vector<std::pair<double, double>>{
           {0, 10}, {-1, 10}, {-1, 100}, {-2, 3}, {-3, 100}, {-3, 1.001}, {0, 1.0001}}) {
    SCOPED_TRACE("alpha " + std::to_string(alpha) + " omega " + std::to_string(omega) + " seed " +
                 std::to_string(kGenerateSeed));
    const auto s = spec(3, 20000, 0.3, alpha, omega, Placement::random);
    const Packing p = generate_packing(s);
    const auto dist = make_distribution(s);
    const PackingQuality q = assess_packing(p, dist.get());
    EXPECT_GT(q.ks_pvalue, kMinKsPvalue) << "KS distance " << q.ks_distance;
    for (double r : p.radii) {
      ASSERT_GE(r, 1.0);
      ASSERT_LE(r, omega);
    }
  }
  const Packing mono = generate_packing(spec(3, 100, 0.3, -3, 1, Placement::random));
  for (double r : mono.radii) EXPECT_EQ(r, 1.0);
}

TEST(Generate, AchievedNuIsExact) {
  for (auto pl : {Placement::random, Placement::excluded})
    for (int d : {2, 3}) {
      SCOPED_TRACE("d " + std::to_string(d) + " " + to_string(pl) + " seed " + std::to_string(kGenerateSeed));
      const Packing p = generate_packing(spec(d, 3000, 0.45, -3, 10, pl));
      EXPECT_NEAR(p.packing_fraction() / 0.45, 1.0, kNuTol);
      EXPECT_NEAR(p.num_attrs.at("nu_achieved") / 0.45, 1.0, kNuTol);
    }
}

TEST(Generate, SequentialAdditionHasNoOverlapAndRespectsWalls) {
  for (auto b : {Boundary::periodic, Boundary::walls})
    for (int d : {2, 3}) {
      SCOPED_TRACE(std::string(to_string(b)) + " d " + std::to_string(d) + " seed " + std::to_string(kGenerateSeed));
      const double nu = d == 2 ? 0.4 : 0.6;
      const Packing p = generate_packing(spec(d, 4000, nu, -3, d == 2 ? 20 : 10, Placement::excluded, b));
      EXPECT_EQ(p.str_attrs.at("method"), "rsa");
      const PackingQuality q = assess_packing(p, nullptr);
      EXPECT_EQ(q.max_rel_overlap, 0.0);
      EXPECT_EQ(q.overlapping_pairs, 0u);
      if (b == Boundary::walls)
        for (std::size_t i = 0; i < p.size(); ++i)
          for (int k = 0; k < d; ++k) {
            EXPECT_GE(p.positions[i * d + k], p.radii[i]);
            EXPECT_LE(p.positions[i * d + k], p.box[k] - p.radii[i]);
          }
    }
}

// A bed (placement bed): the spheres rest in the bottom of their walled
// box, packed (their own nu near the dense packing they were made at),
// overlapping less than the relaxation's tolerance, the box's nu exact; the
// same seed gives the same bed; a periodic box and a box nu above the
// limit are refused.
TEST(Generate, BedRestsOnTheFloorWithoutOverlaps) {
  for (int d : {2, 3}) {
    SCOPED_TRACE("d " + std::to_string(d) + " seed " + std::to_string(kGenerateSeed));
    const PackingSpec sp = spec(d, 800, 0.15, -3, 5, Placement::bed, Boundary::walls);
    const Packing p = generate_packing(sp);
    EXPECT_EQ(p.str_attrs.at("method"), "rsa+growth+fire+settled");
    EXPECT_NEAR(p.packing_fraction(), 0.15, kNuTol);
    const PackingQuality q = assess_packing(p, nullptr);
    EXPECT_LT(q.max_rel_overlap, kRelaxedOverlapTol);
    const double packed = p.num_attrs.at("bed_packing_fraction");  // the nu it was made at, in the bottom
    double top = 0, volume = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      for (int k = 0; k < d; ++k) {
        EXPECT_GE(p.positions[i * d + k], p.radii[i] * (1 - kRelaxedOverlapTol));
        EXPECT_LE(p.positions[i * d + k], p.box[k] - p.radii[i] * (1 - kRelaxedOverlapTol));
      }
      top = std::max(top, p.positions[i * d + d - 1] + p.radii[i]);
      volume += d == 2 ? M_PI * p.radii[i] * p.radii[i] : 4 * M_PI / 3 * std::pow(p.radii[i], 3);
    }
    // Its height: what the packed nu takes, give or take a top layer of
    // the largest spheres; far below the box's top.
    const double floor_area = d == 2 ? p.box[0] : p.box[0] * p.box[1];
    const double height = volume / (floor_area * packed);
    const double rmax = *std::max_element(p.radii.begin(), p.radii.end());
    EXPECT_LT(top, height + 4 * rmax);
    EXPECT_GT(top, 0.8 * height);
    EXPECT_LT(top, 0.5 * p.box[d - 1]);
    EXPECT_EQ(generate_packing(sp).positions, p.positions);
  }
  EXPECT_THROW(generate_packing(spec(3, 500, 0.15, -3, 5, Placement::bed, Boundary::periodic)), InputError);
  EXPECT_THROW(generate_packing(spec(3, 500, 0.35, -3, 5, Placement::bed, Boundary::walls)), InputError);
  EXPECT_EQ(parse_placement("bed"), Placement::bed);
}

TEST(Generate, RandomPlacementKeepsCentresInsideWalls) {
  const Packing p = generate_packing(spec(3, 5000, 0.3, 0, 10, Placement::random, Boundary::walls));
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(p.positions[i * 3 + k], p.radii[i]);
      EXPECT_LE(p.positions[i * 3 + k], p.box[k] - p.radii[i]);
    }
}

TEST(Generate, SlabCountingNoiseOfManufacturedPackings) {
  // Equal particles: the expected slab deviation is sqrt((1 - 1/S) S / N)
  // = 0.1 for N = 900 and S = 10, whatever the centres.
  Packing p;
  p.d = 3;
  p.box = {100, 100, 100};
  for (int i = 0; i < 900; ++i) {
    p.radii.push_back(1.0);
    for (double c : {5.0 + (i % 10) * 10.0, 50.0, 50.0}) p.positions.push_back(c);
  }
  const PackingQuality q = assess_packing(p, nullptr, false);
  EXPECT_NEAR(q.slab_noise, 0.1, 1e-12);
  // One particle of 1000x the volume of the others: the noise is its own.
  p.radii[0] = 10.0;
  const PackingQuality big = assess_packing(p, nullptr, false);
  const double s1 = 1000.0 + 899.0, s2 = 1e6 + 899.0;
  EXPECT_NEAR(big.slab_noise, std::sqrt(0.9 * 10 * s2) / s1, 1e-12);
  ASSERT_EQ(big.band_slab_noise.size(), static_cast<std::size_t>(kSizeBands));
}

TEST(Generate, GrowthReachesDenseEqualVolumeDistribution) {
  // alpha = 0: sequential addition stalls well below 0.6; growth + FIRE finishes.
  for (auto b : {Boundary::periodic, Boundary::walls}) {
    SCOPED_TRACE(std::string(to_string(b)) + " seed " + std::to_string(kGenerateSeed));
    const Packing p = generate_packing(spec(3, 1500, 0.6, 0, 4, Placement::excluded, b));
    EXPECT_EQ(p.str_attrs.at("method"), "rsa+growth+fire");
    EXPECT_NEAR(p.packing_fraction() / 0.6, 1.0, kNuTol);
    const PackingQuality q = assess_packing(p, nullptr);
    EXPECT_LE(q.max_rel_overlap, kRelaxedOverlapTol);
  }
}

// The FIRE relaxation sums forces over its Verlet lists, which a contact
// list without skin builds from the inflated spheres (gen_relax.cpp): they
// must hold exactly the brute-force pairs, each partner list ascending,
// whatever order the grid found them in, on any number of threads (else the
// packing of a seed changes with the grid's traversal).
template <int D, Boundary B>
void expect_canonical_lists(std::uint64_t seed) {
  const auto sc = test::random_scene<D>(1500, 0.5, -2, 10, B, seed);
  const auto brute = test::brute_pairs<D, B>(sc);
  for (const int threads : {1, 2, 3}) {
    ListBox<D> box;
    box.side = sc.box;
    box.periodic.fill(B == Boundary::periodic);
    ContactListParams params;
    params.threads = threads;
    ContactList<D> list(box, params);
    list.update(std::span<const Sphere<D>>(sc.spheres));
    const std::span<const std::uint32_t> start = list.start(), nbr = list.partners();
    std::vector<test::Pair> got;
    for (std::uint32_t i = 0; i + 1 < start.size(); ++i)
      for (std::uint32_t m = start[i]; m < start[i + 1]; ++m) got.emplace_back(i, nbr[m]);
    EXPECT_FALSE(got.empty());
    EXPECT_EQ(got, brute) << "seed " << seed << ", " << threads << " threads";
  }
}

TEST(Generate, NeighbourListsAreTheBrutePairsInCanonicalOrder) {
  expect_canonical_lists<3, Boundary::periodic>(kGenerateSeed);
  expect_canonical_lists<3, Boundary::walls>(kGenerateSeed + 1);
  expect_canonical_lists<2, Boundary::periodic>(kGenerateSeed + 2);
  expect_canonical_lists<2, Boundary::walls>(kGenerateSeed + 3);
}

TEST(Generate, SameSeedSamePacking) {
  // Same seed: identical datasets and attributes. (Byte-identical files also
  // need HDF5's object modification times switched off in the writer.)
  const fs::path dir = temp_dir("bits");
  const auto s = spec(3, 2000, 0.5, -2, 10, Placement::excluded);
  write_packing((dir / "a.h5").string(), generate_packing(s));
  write_packing((dir / "b.h5").string(), generate_packing(s));
  const Packing a = read_packing((dir / "a.h5").string()), b = read_packing((dir / "b.h5").string());
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.radii, b.radii);
  EXPECT_EQ(a.box, b.box);
  EXPECT_EQ(a.num_attrs, b.num_attrs);
  EXPECT_EQ(a.str_attrs, b.str_attrs);
  auto other = s;
  other.seed = kGenerateSeed + 1;
  EXPECT_NE(generate_packing(other).positions, a.positions);
  fs::remove_all(dir);
}

TEST(Generate, CacheGeneratesOnceAndChecksBeforeReuse) {
  const fs::path dir = temp_dir("cache");
  const auto s = spec(3, 1000, 0.4, -3, 10, Placement::excluded);
  const std::string path = packing_cache_path(s, dir.string());
  EXPECT_EQ(fs::path(path).parent_path(), dir);
  EXPECT_EQ(fs::path(path).extension(), ".h5");
  auto other = s;
  other.seed += 1;
  EXPECT_NE(packing_cache_path(other, dir.string()), path);
  const Packing a = cached_packing(s, dir.string());
  ASSERT_TRUE(fs::exists(path));
  const auto written = fs::last_write_time(path);
  const Packing b = cached_packing(s, dir.string());
  EXPECT_EQ(fs::last_write_time(path), written);  // reused, not rewritten
  EXPECT_EQ(a.positions, b.positions);
  // A corrupt cache file is detected and replaced.
  { std::ofstream(path, std::ios::trunc) << "not hdf5"; }
  const Packing c = cached_packing(s, dir.string());
  EXPECT_EQ(a.positions, c.positions);
  fs::remove_all(dir);
}

TEST(Generate, EquilibrationKeepsRadiiNuAndZeroOverlap) {
  for (auto b : {Boundary::periodic, Boundary::walls}) {
    SCOPED_TRACE(std::string(to_string(b)) + " seed " + std::to_string(kGenerateSeed));
    auto s = spec(3, 3000, 0.55, -3, 10, Placement::excluded, b);
    const Packing before = generate_packing(s);
    s.equilibrate = true;
    const Packing after = generate_packing(s);
    EXPECT_EQ(before.radii, after.radii);
    EXPECT_NE(before.positions, after.positions);
    EXPECT_NEAR(after.packing_fraction() / 0.55, 1.0, kNuTol);
    EXPECT_EQ(assess_packing(after, nullptr).max_rel_overlap, 0.0);
    EXPECT_GT(after.num_attrs.at("equilibration_acceptance"), 0.0);
    EXPECT_GT(after.num_attrs.at("equilibration_swap_acceptance"), 0.0);
  }
  auto s = spec(3, 100, 0.3, -3, 10, Placement::random);
  s.equilibrate = true;
  EXPECT_THROW(generate_packing(s), InputError);
}

// The checkerboard Monte Carlo runs a colour's domains at once, each on its
// own random stream: the packing must not depend on the number of threads
// (8 oversubscribes this 2-core machine), also when the box holds only two
// domains per axis (the fewest excluded-volume placement allows).
TEST(Generate, EquilibrationIsTheSameForAnyThreadCount) {
  struct Case {
    int d;
    std::size_t n;
    double nu, omega;
    Boundary b;
  };
  for (const Case c : {Case{3, 4000, 0.5, 10, Boundary::periodic}, Case{3, 3000, 0.5, 10, Boundary::walls},
                       Case{2, 3000, 0.6, 5, Boundary::periodic}, Case{2, 2000, 0.6, 5, Boundary::walls},
                       Case{3, 300, 0.3, 10, Boundary::periodic}, Case{3, 60, 0.3, 4, Boundary::walls}}) {
    SCOPED_TRACE("d " + std::to_string(c.d) + " n " + std::to_string(c.n) + " " + to_string(c.b) + " seed " +
                 std::to_string(kGenerateSeed));
    auto s = spec(c.d, c.n, c.nu, -3, c.omega, Placement::excluded, c.b);
    s.equilibrate = true;
    s.sweeps = 30;
    s.threads = 1;
    const Packing one = generate_packing(s);
    EXPECT_EQ(assess_packing(one, nullptr).max_rel_overlap, 0.0);
    for (const int t : {2, 3, 8}) {
      s.threads = t;
      const Packing many = generate_packing(s);
      EXPECT_EQ(one.positions, many.positions) << t << " threads";
      EXPECT_EQ(one.num_attrs.at("equilibration_acceptance"), many.num_attrs.at("equilibration_acceptance"));
    }
  }
}

// The Metropolis trials' overlap tests on move lists (gen_move_lists.hpp)
// must decide every trial as the insertion grid does: the same packing bit
// for bit and the same acceptance totals, in 2D and 3D, with walls and
// periodic, for sizes from one octave to five (at omega = 30 from
// sequential addition the lists turn themselves off after a sweep), and on
// two threads (where the grid alone tests). Compressed packings start with
// overlapping pairs, which only the grid's test saw before the lists.
TEST(Generate, MoveListsDecideAsTheGrid) {
  struct Case {
    int d;
    std::size_t n;
    double nu, alpha, omega;
    Boundary b;
    ExcludedMethod m;
    int threads, sweeps;
  };
  // The last case runs long enough for the lists to be made afresh several
  // times (kRelistPerSphere relists per sphere).
  for (const Case c : {Case{3, 4000, 0.6, -3, 10, Boundary::periodic, ExcludedMethod::growth, 1, 40},
                       Case{3, 3000, 0.6, 0, 10, Boundary::walls, ExcludedMethod::growth, 1, 40},
                       Case{3, 8000, 0.45, -3, 30, Boundary::periodic, ExcludedMethod::automatic, 1, 30},
                       Case{3, 3000, 0.3, -1, 2, Boundary::walls, ExcludedMethod::automatic, 2, 40},
                       Case{2, 3000, 0.7, -3, 10, Boundary::walls, ExcludedMethod::growth, 1, 40},
                       Case{2, 1500, 0.5, 0, 5, Boundary::periodic, ExcludedMethod::automatic, 1, 400}}) {
    SCOPED_TRACE("d " + std::to_string(c.d) + " n " + std::to_string(c.n) + " omega " + std::to_string(c.omega) + " " +
                 to_string(c.b) + " threads " + std::to_string(c.threads) + " seed " + std::to_string(kGenerateSeed));
    auto s = spec(c.d, c.n, c.nu, c.alpha, c.omega, Placement::excluded, c.b);
    s.method = c.m;
    s.threads = c.threads;
    const Packing placed = generate_packing(s);
    s.equilibrate = true;
    s.sweeps = c.sweeps;
    s.overlap_search = OverlapSearch::grid;
    const Packing grid = generate_packing(s, &placed);
    s.overlap_search = OverlapSearch::lists;
    const Packing lists = generate_packing(s, &placed);
    EXPECT_EQ(grid.positions, lists.positions);
    for (const char* k : {"equilibration_moves_accepted", "equilibration_swaps_accepted"})
      EXPECT_EQ(grid.num_attrs.at(k), lists.num_attrs.at(k)) << k;
    EXPECT_LE(assess_packing(lists, nullptr).max_rel_overlap, kRelaxedOverlapTol);
  }
}

// The placement method: growth always compresses (sequential addition at
// nu = 0.35, then growth + FIRE), even where sequential addition alone
// would reach nu; rsa refuses where sequential addition stalls, naming the
// field; random centres take no method.
TEST(Generate, PlacementMethodIsObeyed) {
  auto s = spec(3, 3000, 0.5, -3, 10, Placement::excluded, Boundary::walls);
  EXPECT_EQ(generate_packing(s).str_attrs.at("method"), "rsa");
  s.method = ExcludedMethod::growth;
  const Packing grown = generate_packing(s);
  EXPECT_EQ(grown.str_attrs.at("method"), "rsa+growth+fire");
  EXPECT_NEAR(grown.packing_fraction() / 0.5, 1.0, kNuTol);
  EXPECT_LE(assess_packing(grown, nullptr).max_rel_overlap, kRelaxedOverlapTol);
  auto stalls = spec(3, 400, 0.45, 0, 1.5, Placement::excluded);
  stalls.method = ExcludedMethod::rsa;
  try {
    generate_packing(stalls);
    ADD_FAILURE() << "sequential addition alone should stall";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("method"), std::string::npos) << e.what();
  }
  auto random = spec(3, 100, 0.3, -3, 10, Placement::random);
  random.method = ExcludedMethod::growth;
  EXPECT_THROW(generate_packing(random), InputError);
  EXPECT_THROW(parse_excluded_method("shake"), InputError);
}

// A long equilibration can be resumed: from a finished stage (fewer sweeps,
// through a file, so the recorded generator state is what resumes), from a
// checkpoint of a run killed part-way, from the placement (by sequential
// addition or compression), and through the cache. Each gives the
// uninterrupted run's packing, bit for bit, and its acceptance totals.
TEST(Generate, ResumedEquilibrationIsTheUninterruptedOne) {
  const fs::path dir = temp_dir("resume");
  for (const auto& [d, b] : std::vector<std::pair<int, Boundary>>{
           {3, Boundary::periodic}, {3, Boundary::walls}, {2, Boundary::walls}}) {
    SCOPED_TRACE("d " + std::to_string(d) + " " + to_string(b) + " seed " + std::to_string(kGenerateSeed));
    auto s = spec(d, 2000, 0.5, -3, 5, Placement::excluded, b);
    s.equilibrate = true;
    s.sweeps = 30;
    const Packing whole = generate_packing(s);
    const auto same = [&](const Packing& p) {
      EXPECT_EQ(p.positions, whole.positions);
      EXPECT_EQ(p.radii, whole.radii);
      for (const char* a : {"equilibration_acceptance", "equilibration_swap_acceptance", "equilibration_sweeps"})
        EXPECT_EQ(p.num_attrs.at(a), whole.num_attrs.at(a)) << a;
      EXPECT_EQ(p.str_attrs.at("cache_key"), whole.str_attrs.at("cache_key"));
      EXPECT_EQ(p.str_attrs.at("equilibration_rng_state"), whole.str_attrs.at("equilibration_rng_state"));
    };
    // From a finished stage of 10 sweeps, through a file.
    auto s10 = s;
    s10.sweeps = 10;
    write_packing((dir / "s10.h5").string(), generate_packing(s10));
    const Packing stage = read_packing((dir / "s10.h5").string());
    EXPECT_EQ(resume_mismatch(stage, s), "");
    same(generate_packing(s, &stage));
    // From a checkpoint: one after every sweep, the run killed after the 17th.
    const std::vector<Packing> checkpoints = test::checkpoints_until_killed(s, 17);
    ASSERT_EQ(checkpoints.size(), 17u);
    EXPECT_EQ(equilibration_sweeps_done(checkpoints.back()), 17u);
    same(generate_packing(s, &checkpoints.back()));
    // What cannot be resumed.
    auto other = s;
    other.seed += 1;
    EXPECT_NE(resume_mismatch(stage, other), "");
    EXPECT_NE(resume_mismatch(whole, s10), "");  // further than asked
    EXPECT_THROW(generate_packing(s10, &whole), std::invalid_argument);
    // From the placement (sweep 0), through a file; one placed before
    // placements recorded the generator's state cannot start it.
    auto placed = s;
    placed.equilibrate = false;
    write_packing((dir / "placed.h5").string(), generate_packing(placed));
    const Packing placement = read_packing((dir / "placed.h5").string());
    EXPECT_EQ(resume_mismatch(placement, s), "");
    EXPECT_NE(resume_mismatch(placement, other), "");
    same(generate_packing(s, &placement));
    Packing older = placement;
    older.str_attrs.erase("equilibration_rng_state");
    EXPECT_NE(resume_mismatch(older, s), "");
  }
  // From a placement by compression (sequential addition, growth + FIRE).
  {
    auto s = spec(3, 2000, 0.5, -3, 5, Placement::excluded, Boundary::periodic);
    s.method = ExcludedMethod::growth;
    s.equilibrate = true;
    s.sweeps = 20;
    auto placed = s;
    placed.equilibrate = false;
    const Packing placement = generate_packing(placed);
    ASSERT_EQ(placement.str_attrs.at("method"), "rsa+growth+fire");
    const Packing whole = generate_packing(s), resumed = generate_packing(s, &placement);
    EXPECT_EQ(resumed.positions, whole.positions);
    EXPECT_EQ(resumed.str_attrs.at("equilibration_rng_state"), whole.str_attrs.at("equilibration_rng_state"));
  }
  // The cache: 10 sweeps, then 30 resumes them; 20 afterwards starts afresh
  // and leaves the resume file at 30.
  auto s = spec(3, 2000, 0.5, -3, 5, Placement::excluded);
  s.equilibrate = true;
  s.sweeps = 30;
  const Packing whole = generate_packing(s);
  auto s10 = s, s20 = s;
  s10.sweeps = 10;
  s20.sweeps = 20;
  const std::string cache = (dir / "cache").string(), resume = equilibration_resume_path(s, cache);
  EXPECT_EQ(equilibration_resume_path(s10, cache), resume);
  cached_packing(s10, cache);
  EXPECT_EQ(equilibration_sweeps_done(read_packing(resume)), 10u);
  EXPECT_EQ(cached_packing(s, cache).positions, whole.positions);
  EXPECT_EQ(equilibration_sweeps_done(read_packing(resume)), 30u);
  EXPECT_EQ(cached_packing(s20, cache).positions, generate_packing(s20).positions);
  EXPECT_EQ(equilibration_sweeps_done(read_packing(resume)), 30u);
  // A second cache holding only the placement: the equilibration starts from it.
  const std::string cache2 = (dir / "cache2").string();
  auto placed = s;
  placed.equilibrate = false;
  cached_packing(placed, cache2);
  EXPECT_FALSE(fs::exists(equilibration_resume_path(s, cache2)));
  EXPECT_EQ(cached_packing(s, cache2).positions, whole.positions);
  EXPECT_EQ(equilibration_sweeps_done(read_packing(equilibration_resume_path(s, cache2))), 30u);
  fs::remove_all(dir);
}

// Sequential addition tries a particle's trials several at a time on
// threads once particles need many trials: the same packing for any thread
// count, also when it stalls (20 000 trials of one particle) and the growth
// route starts from the generator's state after it.
TEST(Generate, SequentialAdditionIsTheSameForAnyThreadCount) {
  struct Case {
    int d;
    std::size_t n;
    double nu, alpha, omega;
    Boundary b;
  };
  for (const Case c : {Case{3, 4000, 0.55, -3, 10, Boundary::periodic}, Case{3, 3000, 0.5, -3, 10, Boundary::walls},
                       Case{2, 3000, 0.7, -3, 5, Boundary::periodic}, Case{2, 2000, 0.65, -3, 5, Boundary::walls},
                       Case{3, 400, 0.45, 0, 1.5, Boundary::periodic}}) {  // the last stalls: growth + FIRE
    SCOPED_TRACE("d " + std::to_string(c.d) + " n " + std::to_string(c.n) + " " + to_string(c.b) + " seed " +
                 std::to_string(kGenerateSeed));
    auto s = spec(c.d, c.n, c.nu, c.alpha, c.omega, Placement::excluded, c.b);
    s.threads = 1;
    const Packing one = generate_packing(s);
    const bool grown = one.str_attrs.at("method") != "rsa";
    EXPECT_EQ(grown, c.alpha == 0) << "the last case must stall, the others not";
    EXPECT_LE(assess_packing(one, nullptr).max_rel_overlap, grown ? kRelaxedOverlapTol : 0.0);
    for (const int t : {2, 3, 8}) {
      s.threads = t;
      const Packing many = generate_packing(s);
      EXPECT_EQ(one.positions, many.positions) << t << " threads";
      EXPECT_EQ(one.str_attrs.at("method"), many.str_attrs.at("method"));
    }
  }
}

// Growth + FIRE on its own (generate_packing keeps a few thousand spheres on
// one thread): the packing and the FIRE steps do not depend on the number of
// threads, also with ranges of a few hundred spheres and many pairs across
// them.
TEST(Generate, GrowthAndFireIsTheSameForAnyThreadCount) {
  struct Case {
    int d;
    std::size_t n;
    Boundary b;
  };
  for (const Case c : {Case{3, 1500, Boundary::periodic}, Case{3, 1200, Boundary::walls},
                       Case{2, 1500, Boundary::walls}}) {
    SCOPED_TRACE("d " + std::to_string(c.d) + " n " + std::to_string(c.n) + " " + to_string(c.b) + " seed " +
                 std::to_string(kGenerateSeed));
    std::mt19937_64 rng(kGenerateSeed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> radii(c.n), pos(c.n * static_cast<std::size_t>(c.d));
    double volume = 0;
    for (double& r : radii) {
      r = 1 + u(rng);  // radii 1 to 2
      volume += c.d == 3 ? 4.18879020478639 * r * r * r : 3.14159265358979 * r * r;
    }
    const double nu = c.d == 3 ? 0.55 : 0.75, side = std::pow(volume / nu, 1.0 / c.d);
    const std::array<double, 3> box{side, side, c.d == 3 ? side : 0.0};
    for (double& x : pos) x = side * u(rng);  // overlapping at first: FIRE separates them
    const double scale0 = 0.85;  // nine growth steps of kGrowthStep
    detail::RelaxStats one_stats;
    std::vector<double> one = pos;
    Progress quiet(false, "");
    ASSERT_TRUE(detail::grow_and_relax(c.d, c.b, box, radii, scale0, 1, one, quiet, one_stats));
    EXPECT_GE(one_stats.growth_steps, 8);
    EXPECT_GT(one_stats.list_builds, 1);
    for (const int t : {2, 3, 8}) {
      detail::RelaxStats st;
      std::vector<double> many = pos;
      ASSERT_TRUE(detail::grow_and_relax(c.d, c.b, box, radii, scale0, t, many, quiet, st)) << t << " threads";
      EXPECT_EQ(one, many) << t << " threads";
      EXPECT_EQ(one_stats.fire_steps, st.fire_steps) << t << " threads";
      EXPECT_EQ(one_stats.list_builds, st.list_builds) << t << " threads";
    }
  }
}

// A move that would leave its domain is rejected, but the domains shift
// every sweep: particles must still travel further than a domain is wide.
TEST(Generate, EquilibrationCrossesDomains) {
  auto s = spec(3, 1000, 0.05, -3, 1, Placement::excluded, Boundary::walls);
  const Packing before = generate_packing(s);
  s.equilibrate = true;
  s.sweeps = 500;
  const Packing after = generate_packing(s);
  double furthest = 0;  // per axis (all radii are 1)
  for (std::size_t i = 0; i < after.positions.size(); ++i)
    furthest = std::max(furthest, std::abs(after.positions[i] - before.positions[i]));
  const double width = after.box[0] / std::floor(after.box[0] / 2);  // domains: one diameter or a little more
  EXPECT_GT(furthest, width);
}

/// The estimate's exact limits hold to this (the infinite ratio is 1e12).
constexpr double kRcpLimitTol = 1e-5;
/// Regression guard on the 3-D alpha = -3, omega = 100 estimate (0.7803).
constexpr double kRcpRegressionTol = 1e-3;

TEST(Generate, RcpEstimate) {
  EXPECT_NEAR(estimate_rcp(3, PowerLaw(-3, 1)), kMonoRcp3, 1e-9);
  EXPECT_NEAR(estimate_rcp(2, PowerLaw(0, 1)), kMonoRcp2, 1e-9);
  // Two sizes of infinite ratio, best mix: 1 - (1 - beta)^2 (0.8704 for spheres).
  for (const double beta : {kMonoRcp3, kMonoRcp2}) {
    const std::vector<SizeClass> bi{{1e12, 1 / (2 - beta)}, {1, (1 - beta) / (2 - beta)}};
    EXPECT_NEAR(virtual_packing_density(bi, beta), 1 - (1 - beta) * (1 - beta), kRcpLimitTol);
    // Equal sizes in two classes pack as one.
    EXPECT_NEAR(virtual_packing_density({{2, 0.3}, {2, 0.7}}, beta), beta, 1e-12);
  }
  // The generators' stated reference: about 0.8 for 3-D alpha = -3, omega = 100.
  const double wide = estimate_rcp(3, PowerLaw(-3, 100));
  EXPECT_NEAR(wide, 0.7803, kRcpRegressionTol);
  EXPECT_LT(wide, 1 - (1 - kMonoRcp3) * (1 - kMonoRcp3));  // here below the two-scale limit
  EXPECT_GT(wide, estimate_rcp(3, PowerLaw(-3, 10)));     // wider packs denser
  EXPECT_GT(estimate_rcp(3, PowerLaw(-3, 10)), kMonoRcp3);
  EXPECT_GE(wide, estimate_rcp(3, PowerLaw(0, 100)));
  // Stable at the exponents where a moment is a logarithm (alpha = -1, -d-1).
  for (const double a : {-1.0, -4.0}) {
    const double e = estimate_rcp(3, PowerLaw(a, 100));
    EXPECT_TRUE(e > kMonoRcp3 && e < 0.9) << a << " " << e;
  }
  EXPECT_THROW(virtual_packing_density({}, kMonoRcp3), InputError);
  EXPECT_THROW(virtual_packing_density({{1, 1}}, 1.0), InputError);
}

TEST(Generate, BadArgumentsAreRejected) {
  auto good = spec(3, 100, 0.3, -3, 10, Placement::random);
  auto expect_field = [](PackingSpec s, const std::string& field) {
    try {
      generate_packing(s);
      ADD_FAILURE() << "accepted a bad " << field;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), field) << e.what();
    }
  };
  auto s = good; s.d = 4; expect_field(s, "d");
  s = good; s.n = 0; expect_field(s, "n");
  s = good; s.nu = 1.2; expect_field(s, "nu");
  s = good; s.nu = -0.1; expect_field(s, "nu");
  s = good; s.omega = 0.5; expect_field(s, "omega");
  s = good; s.dist = "gaussian"; expect_field(s, "dist");
  s = good; s.dist = "lognormal"; s.sigma = 0; expect_field(s, "sigma");
  EXPECT_THROW(parse_placement("grid"), InputError);
  // Beyond jamming: refused up front with the estimate in the message, nothing generated.
  s = spec(3, 1000, 0.9, 0, 10, Placement::excluded);
  try {
    generate_packing(s);
    ADD_FAILURE() << "accepted nu = 0.9";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "nu");
    EXPECT_NE(std::string(e.what()).find("highest reachable"), std::string::npos) << e.what();
  }
  // The case the old rod estimate let through (0.896), to stall in the growth.
  s = spec(3, 1000, 0.8, -3, 100, Placement::excluded);
  expect_field(s, "nu");
  // Too few particles for the box to hold the largest ones.
  s = spec(3, 3, 0.5, 0, 10, Placement::excluded);
  expect_field(s, "n");
}

}  // namespace
}  // namespace hgrid
