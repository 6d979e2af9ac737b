// ContactList: the contact set at every step of seeded trajectories equals
// an O(N^2) brute force with the box's minimum image per axis, and, where
// every axis has one boundary, a fresh HGrid's set of the same spheres, bit
// for bit; per-axis boundaries, an origin, a compressing box, growing radii,
// inserted particles, 2D and 3D, both search directions, 1 and 2 threads;
// a bad update leaves the list as it was; steady state allocates nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "hgridlab/contacts/contact_history.hpp"
#include "hgridlab/contacts/contact_list.hpp"
#include "support.hpp"

namespace hgrid::test {
namespace {

/// The pairs of the spheres in user coordinates, by brute force: centres
/// relative to the origin, wrapped on periodic axes, the grid's expression
/// per axis.
template <int D>
std::vector<Pair> brute(const std::vector<Sphere<D>>& user, const ListBox<D>& box) {
  std::vector<Sphere<D>> s = user;
  for (auto& p : s)
    for (int k = 0; k < D; ++k) {
      p.x[k] -= box.origin[k];
      if (box.periodic[k]) p.x[k] = detail::wrap(p.x[k], box.side[k]);
    }
  std::vector<Pair> out;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      double d2 = 0.0;
      for (int k = 0; k < D; ++k) {
        double dx = s[j].x[k] - s[i].x[k];
        if (box.periodic[k]) dx = detail::min_image(dx, box.side[k]);
        d2 += dx * dx;
      }
      const double rs = s[i].r + s[j].r;
      if (d2 < rs * rs) out.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
    }
  return out;
}

template <int D>
std::vector<Pair> list_pairs(const ContactList<D>& list) {
  std::vector<Pair> out;
  list.for_each_contact([&](std::uint32_t i, std::uint32_t j) { out.emplace_back(i, j); });
  return out;
}

/// A fresh HGrid's pairs of the same spheres (every axis one boundary).
template <int D, Boundary B>
std::vector<Pair> fresh_grid(const std::vector<Sphere<D>>& user, const ListBox<D>& box) {
  std::vector<Sphere<D>> s = user;
  double rmin = s[0].r, rmax = s[0].r;
  for (auto& p : s) {
    for (int k = 0; k < D; ++k) p.x[k] -= box.origin[k];
    rmin = std::min(rmin, p.r);
    rmax = std::max(rmax, p.r);
  }
  const HGrid<D, B> grid(s, box.side, GridParams{doubling_sizes(rmin, rmax), Search::top_down, 1});
  std::vector<Pair> out;
  grid.for_each_pair([&](std::uint32_t i, std::uint32_t j) { out.emplace_back(i, j); });
  std::sort(out.begin(), out.end());
  return out;
}

struct Case {
  std::array<bool, 3> periodic;
  Search search;
  int threads;
  double skin, skin_rel;
  bool compress = false;  // the box shrinks 0.2 % a step (positions scaled with it)
  bool grow = false;      // the radii grow 0.1 % a step
  bool insert = false;    // 5 particles inserted every 10 steps
  std::uint64_t seed = 1;
  bool far = false;       // periodic coordinates handed over in images up to 5 sides away
};

/// A trajectory of Brownian moves; the list's contacts against the brute
/// force (and a fresh grid, where one boundary holds) at every step.
template <int D>
ContactListStats run_trajectory(const Case& c, std::size_t n = 400, int steps = 60) {
  std::mt19937_64 rng(c.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), u01(0.0, 1.0);
  Scene<D> sc = random_scene<D>(n, 0.35, -2.0, 4.0, Boundary::walls, c.seed);
  ListBox<D> box;
  for (int k = 0; k < D; ++k) {
    box.side[k] = sc.box[k];
    box.origin[k] = (k == 0 ? -3.5 : 12.25) * (k + 1);
    box.periodic[k] = c.periodic[k];
  }
  std::vector<Sphere<D>> user = sc.spheres;
  for (auto& p : user)
    for (int k = 0; k < D; ++k) p.x[k] += box.origin[k];
  ContactListParams params;
  params.search = c.search;
  params.threads = c.threads;
  params.skin = c.skin;
  params.skin_rel = c.skin_rel;
  ContactList<D> list(box, params);
  bool all_periodic = true, all_walls = true;
  for (int k = 0; k < D; ++k) (c.periodic[k] ? all_walls : all_periodic) = false;
  const double step = 0.03;  // per axis, in units of the smallest radius
  for (int t = 0; t < steps; ++t) {
    if (t > 0) {
      if (c.compress) {
        ListBox<D> nb = box;
        for (int k = 0; k < D; ++k) nb.side[k] = box.side[k] * 0.998;
        for (auto& p : user)
          for (int k = 0; k < D; ++k) p.x[k] = box.origin[k] + (p.x[k] - box.origin[k]) * 0.998;
        box = nb;
        list.set_box(box);
      }
      for (auto& p : user) {
        for (int k = 0; k < D; ++k) {
          double x = p.x[k] + step * u(rng);
          if (!box.periodic[k]) x = std::clamp(x, box.origin[k], box.origin[k] + box.side[k]);
          // periodic axes: left unwrapped half the time, as codes that keep images hand them over
          else if (t % 2) x = box.origin[k] + detail::wrap(x - box.origin[k], box.side[k]);
          p.x[k] = x;
        }
        if (c.grow) p.r *= 1.001;
        if (c.far)
          for (int k = 0; k < D; ++k)
            if (box.periodic[k])
              p.x[k] = box.origin[k] + detail::wrap(p.x[k] - box.origin[k], box.side[k]) +
                       box.side[k] * std::floor(11 * u01(rng) - 5);
      }
      if (c.insert && t % 10 == 0)
        for (int m = 0; m < 5; ++m) {
          Sphere<D> p;
          for (int k = 0; k < D; ++k) p.x[k] = box.origin[k] + u01(rng) * box.side[k];
          p.r = 1.0 + 3.0 * u01(rng);
          user.push_back(p);
        }
    }
    list.update(user);
    const auto got = list_pairs(list);
    const auto want = brute(user, box);
    if (got != want) {
      ADD_FAILURE() << "D = " << D << ", step " << t << ", seed " << c.seed << ": " << got.size()
                    << " contacts, brute force " << want.size();
      break;
    }
    if ((all_walls && got != fresh_grid<D, Boundary::walls>(user, box)) ||
        (all_periodic && got != fresh_grid<D, Boundary::periodic>(user, box))) {
      ADD_FAILURE() << "D = " << D << ", step " << t << ", seed " << c.seed << ": not a fresh grid's pairs";
      break;
    }
    // The compressed rows and the image shifts agree with the pairs.
    EXPECT_EQ(list.start().back(), list.contacts());
    if (!got.empty()) {
      const auto [i, j] = got[got.size() / 2];
      const auto sh = list.image_shift(i, j), d = list.displacement(i, j);
      for (int k = 0; k < D; ++k) EXPECT_EQ(d[k], list.spheres()[j].x[k] - list.spheres()[i].x[k] + sh[k]);
    }
  }
  return list.stats();
}

constexpr std::array<bool, 3> kWalls{false, false, false}, kPeriodic{true, true, true}, kPour{true, true, false},
    kSlab{false, true, false};

TEST(ContactList, MatchesBruteForceAndFreshGridEveryStep) {
  std::uint64_t seed = 11;
  for (const auto& per : {kWalls, kPeriodic, kPour, kSlab})
    for (const Search s : {Search::top_down, Search::bottom_up})
      for (const int threads : {1, 2}) {
        const Case c{per, s, threads, 0.4, 0.05, false, false, false, seed++};
        SCOPED_TRACE(testing::Message() << "periodic " << per[0] << per[1] << per[2] << ", " << to_string(s)
                                        << ", threads " << threads << ", seed " << c.seed);
        const auto st3 = run_trajectory<3>(c);
        const auto st2 = run_trajectory<2>(c);
        // With a skin the list is rebuilt far less often than every step.
        EXPECT_LT(st3.builds, st3.steps / 3);
        EXPECT_LT(st2.builds, st2.steps / 3);
      }
}

TEST(ContactList, ZeroSkinRebuildsEveryStepAndStaysExact) {
  const auto st = run_trajectory<3>(Case{kPour, Search::bottom_up, 1, 0.0, 0.0, false, false, false, 5}, 300, 20);
  EXPECT_EQ(st.builds, st.steps);
}

// The travel per step: two particles flying apart, 0.3 a step each, with
// skin 1: the margins (0.5 each) are used up at the second step (0.6 + 0.6
// = 1.2 >= 1), so every build comes two steps after the last, having found
// 1.2 used up; a third particle far away never moves. A new particle count
// rebuilds without travel.
TEST(ContactList, TravelIsTheMarginUsedUpPerStep) {
  ContactList<3> list(ListBox<3>{{100, 100, 100}, {0, 0, 0}, {false, false, false}},
                      ContactListParams{{}, Search::bottom_up, 1, 1.0, 0.0});
  std::vector<Sphere<3>> s = {{{50, 50, 50}, 1.0}, {{53, 50, 50}, 1.0}, {{10, 10, 10}, 1.0}};
  for (int t = 0; t <= 6; ++t) {
    list.update(s);
    s[0].x[0] -= 0.3;
    s[1].x[0] += 0.3;
  }
  const ContactListStats& st = list.stats();
  EXPECT_EQ(st.builds, 4u);  // steps 0, 2, 4, 6
  EXPECT_EQ(st.travel_steps, 6u);
  EXPECT_NEAR(st.travel, 3 * 1.2, 1e-9);
  s.push_back({{20, 20, 20}, 1.0});
  list.update(s);
  EXPECT_EQ(st.builds, 5u);
  EXPECT_EQ(st.travel_steps, 6u);
  EXPECT_EQ(st.travel_one, 0.0);  // no build came one step after another
}

// A list rebuilt at every step measures how the two largest displacements'
// sum grows from one step to two: twice on straight lines.
TEST(ContactList, TravelOverTwoStepsOnStraightLines) {
  ContactList<3> list(ListBox<3>{{100, 100, 100}, {0, 0, 0}, {false, false, true}},
                      ContactListParams{{}, Search::bottom_up, 1, 0.1, 0.0});
  std::vector<Sphere<3>> s = {{{50, 50, 50}, 1.0}, {{53, 50, 50}, 1.0}, {{10, 10, 10}, 1.0}};
  for (int t = 0; t <= 5; ++t) {
    list.update(s);  // every step: each moves 0.3 > the skin
    s[0].x[0] -= 0.3;
    s[1].x[2] += 0.3;
  }
  const ContactListStats& st = list.stats();
  EXPECT_EQ(st.builds, 6u);
  // Builds at steps 2 ... 5 came one step after one that came one step after
  // the build before (steps 1 ... 4 called by displacements; step 0 by the
  // first update, step 1 is the first with one before it).
  EXPECT_NEAR(st.travel_one, 4 * 0.6, 1e-9);
  EXPECT_NEAR(st.travel_two, 4 * 1.2, 1e-9);
}

TEST(ContactList, CompressionGrowthAndInsertion) {
  std::uint64_t seed = 101;
  for (const auto& per : {kWalls, kPeriodic, kPour})
    for (const int threads : {1, 2}) {
      SCOPED_TRACE(testing::Message() << "periodic " << per[0] << per[1] << per[2] << ", threads " << threads);
      run_trajectory<3>(Case{per, Search::bottom_up, threads, 0.3, 0.05, true, false, false, seed++});
      run_trajectory<2>(Case{per, Search::top_down, threads, 0.3, 0.05, false, true, false, seed++});
      run_trajectory<3>(Case{per, Search::top_down, threads, 0.3, 0.05, false, false, true, seed++});
      run_trajectory<2>(Case{per, Search::bottom_up, threads, 0.2, 0.0, true, true, true, seed++});
    }
}

// Images many sides away in a box that shrinks: a coordinate that stays put
// while the side changes is a particle that moved (the displacements are
// taken on the wrapped centres).
TEST(ContactList, FarImagesInAChangingBox) {
  std::uint64_t seed = 201;
  for (const auto& per : {kPeriodic, kPour})
    for (const int threads : {1, 2}) {
      SCOPED_TRACE(testing::Message() << "periodic " << per[0] << per[1] << per[2] << ", threads " << threads);
      Case c{per, Search::bottom_up, threads, 0.3, 0.0, true, false, false, seed++};
      c.far = true;
      run_trajectory<3>(c);
      c.seed = seed++;
      run_trajectory<2>(c);
    }
}

TEST(ContactList, ManyThreadsSamePairsInSameOrder) {
  // Blocks of rows are cut per 2048 particles: enough particles for 4 blocks.
  Scene<3> sc = random_scene<3>(10000, 0.3, -3.0, 5.0, Boundary::periodic, 7);
  ListBox<3> box{sc.box, {}, kPeriodic};
  std::vector<std::vector<Pair>> got;
  for (const int threads : {1, 4}) {
    ContactList<3> list(box, ContactListParams{{}, Search::bottom_up, threads, 0.3, 0.0});
    list.update(sc.spheres);
    for (auto& p : sc.spheres) p.x[0] += 0.01;
    list.update(sc.spheres);
    for (auto& p : sc.spheres) p.x[0] -= 0.01;
    got.push_back(list_pairs(list));
  }
  EXPECT_EQ(got[0], got[1]);
  EXPECT_EQ(got[0], brute(sc.spheres, box));
}

TEST(ContactList, LeavingAWalledAxisIsOneErrorAndChangesNothing) {
  Scene<3> sc = random_scene<3>(200, 0.3, 0.0, 2.0, Boundary::walls, 3);
  ListBox<3> box{sc.box, {1.0, 2.0, 3.0}, kPour};
  for (auto& p : sc.spheres)
    for (int k = 0; k < 3; ++k) p.x[k] += box.origin[k];
  ContactList<3> list(box, ContactListParams{{}, Search::bottom_up, 1, 0.5, 0.0});
  list.update(sc.spheres);
  const auto before = list_pairs(list);
  const auto stats = list.stats();
  auto moved = sc.spheres;
  moved[7].x[2] = box.origin[2] + box.side[2] + 0.5;  // through the top
  try {
    list.update(moved);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "position");
    EXPECT_NE(std::string(e.what()).find("particle 7 left the walled axis 3"), std::string::npos) << e.what();
  }
  EXPECT_EQ(list_pairs(list), before);
  EXPECT_EQ(list.stats().steps, stats.steps);
  // A periodic axis wraps instead.
  moved = sc.spheres;
  moved[7].x[0] += 3 * box.side[0];
  list.update(moved);
  EXPECT_EQ(list_pairs(list), brute(moved, box));
  // Bad parameters name their field.
  EXPECT_THROW((ContactList<3>(box, ContactListParams{{}, Search::bottom_up, 1, -1.0, 0.0})), InputError);
  ListBox<3> flat = box;
  flat.side[1] = 0;
  EXPECT_THROW(list.set_box(flat), InputError);
  ListBox<3> other = box;
  other.periodic[2] = true;
  EXPECT_THROW(list.set_box(other), InputError);
}

TEST(ContactList, SteadyStateAllocatesNothing) {
  if (!counts_allocations()) GTEST_SKIP() << "allocations are not counted under AddressSanitizer";
  const Scene<3> sc = random_scene<3>(3000, 0.4, -3.0, 4.0, Boundary::walls, 9);
  // A breathing box (the periodic side 0.5 % shorter for four steps, the
  // centres scaled with it, then back) and particles moving back and forth
  // within their skins: the sizes repeat every eight steps, and the list is
  // rebuilt (in the new box) when the box changes, else only tested.
  std::vector<Sphere<3>> s = sc.spheres;
  ListBox<3> box{sc.box, {}, kPour};
  ContactList<3> list(box, ContactListParams{{}, Search::bottom_up, 1, 0.2, 0.0});
  const auto step = [&](int t) {
    const double f = t % 8 < 4 ? 1.0 : 0.995;
    box.side[0] = sc.box[0] * f;
    for (std::size_t i = 0; i < s.size(); ++i)
      for (int k = 0; k < 3; ++k)
        s[i].x[k] = std::clamp((k == 0 ? f : 1.0) * sc.spheres[i].x[k] + (t % 2 ? 0.03 : 0.0), 0.0, box.side[k]);
    list.set_box(box);
    list.update(s);
  };
  for (int t = 0; t < 16; ++t) step(t);  // the arrays reach their sizes
  const std::uint64_t builds = list.stats().builds;
  const std::size_t before = allocations();
  for (int t = 16; t < 48; ++t) step(t);
  EXPECT_EQ(allocations() - before, 0u);
  EXPECT_GT(list.stats().builds, builds + 2);                 // the counted steps include rebuilds
  EXPECT_LT(list.stats().builds, list.stats().steps);          // and steps that only test
  EXPECT_EQ(list_pairs(list), brute(s, box));
}

}  // namespace
}  // namespace hgrid::test

namespace hgrid::test {
namespace {

/// Each contact's value is its key (ids) the first time it is seen, carried
/// after: a value that comes back different, or a new contact with a
/// non-default value, shows a lost or misplaced history.
TEST(ContactHistory, CarriesValuesByIdsThroughReorderingInsertionAndRemoval) {
  Scene<3> sc = random_scene<3>(600, 0.35, -2.0, 3.0, Boundary::periodic, 31);
  ListBox<3> box{sc.box, {}, kPeriodic};
  ContactList<3> list(box, ContactListParams{{}, Search::bottom_up, 1, 0.3, 0.0});
  ContactHistory<std::uint64_t> hist;
  std::vector<std::uint32_t> ids(sc.spheres.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<std::uint32_t>(1000 + 3 * i);  // increasing
  std::uint32_t next_id = 1000 + 3 * static_cast<std::uint32_t>(ids.size());
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::set<std::uint64_t> before;  // the contacts (as id keys) of the last step
  std::size_t carried_total = 0;
  for (int t = 0; t < 40; ++t) {
    if (t > 0) {
      for (auto& p : sc.spheres)
        for (int k = 0; k < 3; ++k) p.x[k] += 0.05 * u(rng);
      if (t % 7 == 0) {  // reorder: a shuffle of particles with their ids
        std::vector<std::size_t> perm(ids.size());
        for (std::size_t i = 0; i < perm.size(); ++i) perm[i] = i;
        std::shuffle(perm.begin(), perm.end(), rng);
        auto s2 = sc.spheres;
        auto id2 = ids;
        for (std::size_t i = 0; i < perm.size(); ++i) s2[i] = sc.spheres[perm[i]], id2[i] = ids[perm[i]];
        sc.spheres.swap(s2);
        ids.swap(id2);
      }
      if (t % 5 == 0) {  // remove two, insert three
        sc.spheres.erase(sc.spheres.begin() + 10, sc.spheres.begin() + 12);
        ids.erase(ids.begin() + 10, ids.begin() + 12);
        for (int m = 0; m < 3; ++m) {
          sc.spheres.push_back(Sphere<3>{{sc.box[0] * 0.5 + m, sc.box[1] * 0.5, sc.box[2] * 0.5}, 1.5});
          ids.push_back(next_id++);
        }
      }
    }
    list.update(sc.spheres);
    hist.update(list, ids);
    std::set<std::uint64_t> now;
    std::size_t m = 0, carried = 0;
    list.for_each_contact([&](std::uint32_t i, std::uint32_t j) {
      const std::uint64_t a = std::min(ids[i], ids[j]), b = std::max(ids[i], ids[j]);
      const std::uint64_t key = (a << 32) | b;
      now.insert(key);
      std::uint64_t& v = hist.values()[m++];
      if (before.count(key)) {
        EXPECT_EQ(v, key) << "step " << t << ": a persisting contact lost its value";
        ++carried;
      } else {
        EXPECT_EQ(v, 0u) << "step " << t << ": a new contact came with a value";
      }
      v = key;
    });
    EXPECT_EQ(hist.carried(), carried);
    carried_total += carried;
    before.swap(now);
  }
  EXPECT_GT(carried_total, 1000u);
}

}  // namespace
}  // namespace hgrid::test

namespace hgrid::test {
namespace {

/// A Lees-Edwards box whose offset grows every step (the tilt flipping by
/// lx at LAMMPS's limit), and a triclinic box whose three tilts drift: at
/// every step the contacts equal the tilted brute force (3^d images around
/// the rounding) and a fresh TiltedHGrid's, bit for bit.
template <int D>
void check_sheared(std::uint64_t seed, bool lees_edwards, int threads) {
  Scene<D> sc = random_scene<D>(500, 0.3, -2.0, 3.0, Boundary::periodic, seed);
  ListBox<D> box;
  box.side = sc.box;
  box.periodic.fill(true);
  box.triclinic = true;
  for (int k = 0; k < D; ++k) box.origin[k] = 2.5 * (k + 1);
  std::vector<Sphere<D>> user = sc.spheres;
  for (auto& p : user)
    for (int k = 0; k < D; ++k) p.x[k] += box.origin[k];
  ContactList<D> list(box, ContactListParams{{}, Search::bottom_up, threads, 0.4, 0.0});
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double offset = lees_edwards ? 0.47 * box.side[0] : 0.0;
  box.tilt = TiltedBox<D>::lees_edwards(box.side, offset).tilt;
  list.set_box(box);
  for (int t = 0; t < 80; ++t) {
    if (t > 0) {
      for (auto& p : user)
        for (int k = 0; k < D; ++k) p.x[k] += 0.03 * u(rng);
      if (lees_edwards) {
        offset += 0.002 * box.side[0];  // from 0.47 lx: past lx/2 after 15 steps, where the tilt flips
        box.tilt = TiltedBox<D>::lees_edwards(box.side, offset).tilt;
      } else {
        for (int k = 0; k < (D == 2 ? 1 : 3); ++k)
          box.tilt[k] = std::clamp(box.tilt[k] + 0.01 * box.side[0] * u(rng), -0.3 * box.side[0], 0.3 * box.side[0]);
      }
      list.set_box(box);
    }
    list.update(user);
    std::vector<Sphere<D>> local = user;
    for (auto& p : local)
      for (int k = 0; k < D; ++k) p.x[k] -= box.origin[k];
    TiltedBox<D> tb{box.side, box.tilt};
    if constexpr (D == 2) tb.tilt[1] = tb.tilt[2] = 0;
    std::vector<Pair> want;
    brute_force_pairs_tilted<D>(local, tb, [&](std::uint32_t i, std::uint32_t j) { want.emplace_back(i, j); });
    double rmin = local[0].r, rmax = rmin;
    for (const auto& p : local) rmin = std::min(rmin, p.r), rmax = std::max(rmax, p.r);
    const TiltedHGrid<D> fresh(local, tb, GridParams{doubling_sizes(rmin, rmax), Search::top_down, 1});
    std::vector<Pair> grid;
    fresh.for_each_pair([&](std::uint32_t i, std::uint32_t j) { grid.emplace_back(i, j); });
    std::sort(grid.begin(), grid.end());
    const auto got = list_pairs(list);
    if (got != want || got != grid) {
      ADD_FAILURE() << "D = " << D << ", step " << t << ", seed " << seed << ", tilt xy " << tb.tilt[0] << ": "
                    << got.size() << " contacts, brute force " << want.size() << ", fresh grid " << grid.size();
      return;
    }
    if (!got.empty()) {  // the image shift makes the displacement
      const auto [i, j] = got[got.size() / 3];
      const auto d = list.displacement(i, j);
      double d2 = 0;
      for (int k = 0; k < D; ++k) d2 += d[k] * d[k];
      EXPECT_LT(d2, (local[i].r + local[j].r) * (local[i].r + local[j].r));
    }
  }
  EXPECT_LT(list.stats().builds, list.stats().steps);
}

/// A tilted box narrower than the inflated diameters reach (a third to
/// nine tenths of 4 R_max wide): few large spheres moving, a Lees-Edwards
/// offset growing through the flip; at every step the contacts equal the
/// tilted brute force and a fresh TiltedHGrid's, and each contact's image
/// shift gives its displacement.
template <int D>
void check_narrow_sheared(std::uint64_t seed, double width_over_4r, int threads) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double rmax = 1.0, skin = 0.3;
  ListBox<D> box;
  for (int k = 0; k < D; ++k) box.side[k] = width_over_4r * 4 * (rmax + skin / 2) * (1 + 0.25 * k);
  box.periodic.fill(true);
  box.triclinic = true;
  double offset = 0.4 * box.side[0];
  box.tilt = TiltedBox<D>::lees_edwards(box.side, offset).tilt;
  if constexpr (D == 3) box.tilt[2] = -0.3 * box.side[1];
  std::vector<Sphere<D>> user(D == 2 ? 40 : 60);
  for (std::size_t i = 0; i < user.size(); ++i) {
    for (int k = 0; k < D; ++k) user[i].x[k] = u(rng) * box.side[k];
    user[i].r = i == 0 ? rmax : 0.2 + 0.8 * u(rng);
  }
  ContactList<D> list(box, ContactListParams{{}, Search::bottom_up, threads, skin, 0.0});
  std::uniform_real_distribution<double> step(-1.0, 1.0);
  for (int t = 0; t < 60; ++t) {
    if (t > 0) {
      for (auto& p : user)
        for (int k = 0; k < D; ++k) p.x[k] += 0.04 * step(rng);
      offset += 0.01 * box.side[0];  // past lx/2 after 10 steps: the tilt flips
      box.tilt[0] = TiltedBox<D>::lees_edwards(box.side, offset).tilt[0];
      list.set_box(box);
    }
    list.update(user);
    TiltedBox<D> tb{box.side, box.tilt};
    std::vector<Pair> want;
    brute_force_pairs_tilted<D>(user, tb, [&](std::uint32_t i, std::uint32_t j) { want.emplace_back(i, j); });
    const TiltedHGrid<D> fresh(user, tb, GridParams{doubling_sizes(0.2, rmax), Search::top_down, 1});
    std::vector<Pair> grid;
    fresh.for_each_pair([&](std::uint32_t i, std::uint32_t j) { grid.emplace_back(i, j); });
    std::sort(grid.begin(), grid.end());
    const auto got = list_pairs(list);
    if (got != want || got != grid) {
      ADD_FAILURE() << "D = " << D << ", step " << t << ", seed " << seed << ", width " << tb.min_width()
                    << ": " << got.size() << " contacts, brute force " << want.size() << ", fresh grid "
                    << grid.size();
      return;
    }
    for (const auto& [i, j] : got) {
      const auto d = list.displacement(i, j);
      double d2 = 0;
      for (int k = 0; k < D; ++k) d2 += d[k] * d[k];
      ASSERT_LT(d2, (user[i].r + user[j].r) * (user[i].r + user[j].r)) << "pair " << i << "," << j << " step " << t;
    }
  }
  EXPECT_LT(list.stats().builds, list.stats().steps);
}

TEST(ContactList, TiltedBoxesNarrowerThanTheInflatedDiameters) {
  for (const int threads : {1, 2})
    for (const double w : {0.9, 0.6, 0.35}) {
      SCOPED_TRACE("threads " + std::to_string(threads) + ", width / 4 R_max " + std::to_string(w));
      check_narrow_sheared<2>(401, w, threads);
      check_narrow_sheared<3>(402, w, threads);
    }
}

TEST(ContactList, LeesEdwardsAndDriftingTiltsEveryStep) {
  for (const int threads : {1, 2}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    check_sheared<2>(301, true, threads);
    check_sheared<3>(302, true, threads);
    check_sheared<3>(303, false, threads);
    check_sheared<2>(304, false, threads);
  }
}

}  // namespace
}  // namespace hgrid::test
