// DPM engine: restitution of a resolved head-on collision, energy conservation
// without dissipation, wall bounces, momentum in a periodic box, the time-step
// check, the effect counters (switched-off effects do no work) and a
// trajectory that does not depend on the grid.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hgridlab/dpm/simulation.hpp"
#include "hgridlab/base/error.hpp"

namespace hgrid::dpm {
namespace {

constexpr double kRestitutionTol = 1e-6;   // |e_measured - e_set|
constexpr double kEnergyDriftTol = 1e-4;   // relative, 1e4 steps, e = 1
constexpr double kMomentumTol = 1e-12;     // relative to sum m |v|
constexpr double kWallRestitutionTol = 1e-4;
constexpr std::uint64_t kDpmSeed = 20140357;

Packing make_packing(int d, Boundary b, std::array<double, 3> box, std::vector<double> pos, std::vector<double> radii) {
  Packing p;
  p.d = d;
  p.boundary = b;
  p.box = box;
  p.positions = std::move(pos);
  p.radii = std::move(radii);
  return p;
}

DpmConfig base_config(int d, Boundary b, std::array<double, 3> box, double e, double dt_over_tc) {
  DpmConfig c;
  c.d = d;
  c.boundary = b;
  c.box = box;
  c.contact_time = 1.0;
  c.restitution = e;
  c.dt = dt_over_tc;
  c.sizes = {2.5};
  return c;
}

// Two unit spheres approach head-on with relative speed 2; the initial gap is
// closed at t = dt/2, so the contact starts (and, lasting t_c = n dt, ends) on
// a half step where velocity Verlet's impulse cells begin and end.
double head_on_restitution(int d, double e) {
  const double dt = 1.0 / 2000, gap = 2.0 * dt / 2;
  std::vector<double> pos(2 * d, 10.0), vel(2 * d, 0.0);
  pos[0] = 10.0 - 1.0 - gap / 2;
  pos[d] = 10.0 + 1.0 + gap / 2;
  vel[0] = 1.0;
  vel[d] = -1.0;
  const auto p = make_packing(d, Boundary::walls, {20, 20, 20}, pos, {1.0, 1.0});
  auto sim = make_simulation(base_config(d, Boundary::walls, {20, 20, 20}, e, dt), p, vel);
  sim->run(2300);  // contact over after t_c = 2000 steps
  const auto v = sim->velocities();
  return (v[d] - v[0]) / 2.0;
}

/// An oblique elastic impact of two unit spheres (3D, q = I / (m r^2) = 2/5)
/// with the tangential spring law: approach speed vn along x, tangential
/// relative speed vt along y. Returns the relative translational velocity
/// along y after the contact over the one before. skin: the contact list's.
double oblique_tangential_ratio(double vn, double vt, double mu, double skin) {
  // A stiff contact (t_c = 0.001): the spheres slide at most 0.001 r along
  // each other while in contact, so the contact's normal hardly turns.
  const double tc = 0.001, dt = tc / 400, gap = vn * dt / 2;
  std::vector<double> pos(6, 10.0), vel(6, 0.0);
  pos[0] = 10.0 - 1.0 - gap / 2;
  pos[3] = 10.0 + 1.0 + gap / 2;
  vel[0] = vn / 2, vel[1] = vt / 2;
  vel[3] = -vn / 2, vel[4] = -vt / 2;
  const auto p = make_packing(3, Boundary::walls, {20, 20, 20}, pos, {1.0, 1.0});
  auto c = base_config(3, Boundary::walls, {20, 20, 20}, 1.0, dt);
  c.contact_time = tc;
  c.friction = true;
  c.mu = mu;
  c.friction_damping = 0;
  c.tangential = TangentialLaw::spring;
  c.tangential_stiffness = 2.0 / 7.0;
  c.skin = skin;
  auto sim = make_simulation(c, p, vel);
  sim->run(500);  // t_c = 400 steps
  const auto v = sim->velocities();
  return (v[4] - v[1]) / -vt;
}

/// The spring law's analytic limits (Walton 1993; Luding 2008): sliding all
/// through the contact, the tangential impulse is mu times the normal one,
/// so the relative tangential velocity drops by mu (1 + e) vn; sticking with
/// k_t / k_n = q / (1 + q) = 2/7, the tangential oscillation lasts exactly the
/// contact and the contact point's tangential velocity reverses, leaving the
/// centres (1 - q) / (1 + q) = 3/7 of their relative tangential velocity.
constexpr double kObliqueTol = 0.005;  // dt = t_c / 400: the spring's increments are first order in dt (measured 0.0005 and 0.0021)
TEST(Dpm, TangentialSpringMeetsTheObliqueImpactLimits) {
  const double vn = 1.0;
  const double vt = 1.0, mu = 0.1;  // slides throughout: mu (1 + e) vn (1 + 1/q) = 0.7 < vt
  const double sliding = oblique_tangential_ratio(vn, vt, mu, 0.0);
  const double sticking = oblique_tangential_ratio(vn, 0.2, 10.0, 0.0);  // sticks throughout
  EXPECT_NEAR(sliding, (vt - mu * 2 * vn) / vt, kObliqueTol);
  EXPECT_NEAR(sticking, 3.0 / 7.0, kObliqueTol);
  // The contact list rebuilt at every step (skin 0), several times within
  // the contact (skin 1e-4 r: the springs carried across), or never: the
  // same impact, bit for bit.
  for (const double skin : {1e-4, 1.0}) {
    EXPECT_EQ(oblique_tangential_ratio(vn, vt, mu, skin), sliding) << "skin " << skin;
    EXPECT_EQ(oblique_tangential_ratio(vn, 0.2, 10.0, skin), sticking) << "skin " << skin;
  }
}

TEST(Dpm, HeadOnCollisionGivesTheSetRestitution) {
  for (int d : {2, 3})
    for (double e : {0.5, 0.8, 0.95}) {
      const double got = head_on_restitution(d, e);
      EXPECT_NEAR(got, e, kRestitutionTol) << "d = " << d << ", e = " << e;
    }
}

// Lattice of disks with random velocities in a periodic box.
Packing gas(int d, int per_axis, double spacing, double r, std::vector<double>& vel, double speed, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-speed, speed);
  std::vector<double> pos, radii;
  const int n = d == 2 ? per_axis * per_axis : per_axis * per_axis * per_axis;
  for (int i = 0; i < n; ++i) {
    int rest = i;
    for (int k = 0; k < d; ++k) {
      pos.push_back((rest % per_axis + 0.5) * spacing);
      rest /= per_axis;
      vel.push_back(u(rng));
    }
    radii.push_back(i % 3 == 0 ? r : 0.6 * r);  // bidisperse
  }
  const double a = per_axis * spacing;
  return make_packing(d, Boundary::periodic, {a, a, a}, pos, radii);
}

TEST(Dpm, ElasticGasConservesEnergy) {
  std::vector<double> vel;
  const auto p = gas(2, 10, 3.0, 1.0, vel, 0.2, kDpmSeed);
  SCOPED_TRACE("seed " + std::to_string(kDpmSeed));
  auto c = base_config(2, Boundary::periodic, p.box, 1.0, 1.0 / 50);
  auto sim = make_simulation(c, p, vel);
  const double e0 = sim->kinetic_energy() + sim->elastic_energy();
  sim->run(10000);
  const double e1 = sim->kinetic_energy() + sim->elastic_energy();
  EXPECT_GT(sim->stats().pair_contacts, 1000u);  // the gas did collide
  EXPECT_LT(std::abs(e1 - e0) / e0, kEnergyDriftTol);
}

TEST(Dpm, ParticleBouncesOffEveryWall) {
  const double e = 0.8, dt = 1.0 / 200;
  for (int d : {2, 3})
    for (int axis = 0; axis < d; ++axis)
      for (int side : {0, 1}) {
        std::vector<double> pos(d, 5.0), vel(d, 0.0);
        // Contact starts at t = dt/2 (see head_on_restitution).
        pos[axis] = side == 0 ? 1.0 + 0.5 * dt : 9.0 - 0.5 * dt;
        vel[axis] = side == 0 ? -1.0 : 1.0;
        const auto p = make_packing(d, Boundary::walls, {10, 10, 10}, pos, {1.0});
        auto sim = make_simulation(base_config(d, Boundary::walls, {10, 10, 10}, e, dt), p, vel);
        sim->run(300);
        const auto v = sim->velocities();
        EXPECT_NEAR(v[axis], side == 0 ? e : -e, kWallRestitutionTol) << "d " << d << " axis " << axis << " side " << side;
        EXPECT_GT(sim->stats().wall_contacts, 0u);
      }
}

TEST(Dpm, PeriodicBoxConservesMomentum) {
  for (int d : {2, 3})
    for (bool friction : {false, true}) {
      std::vector<double> vel;
      const auto p = gas(d, d == 2 ? 8 : 4, 2.2, 1.0, vel, 0.5, kDpmSeed + d);
      SCOPED_TRACE("seed " + std::to_string(kDpmSeed + d));
      auto c = base_config(d, Boundary::periodic, p.box, 0.7, 1.0 / 20);
      c.friction = friction;
      auto sim = make_simulation(c, p, vel);
      const auto p0 = sim->momentum();
      double scale = 0;
      for (std::size_t i = 0; i < p.size(); ++i)
        for (int k = 0; k < d; ++k) scale += std::abs(vel[i * d + k]) * M_PI * p.radii[i] * p.radii[i];
      sim->run(2000);
      const auto p1 = sim->momentum();
      EXPECT_GT(sim->stats().pair_contacts, 100u);
      for (int k = 0; k < d; ++k) EXPECT_NEAR(p1[k], p0[k], kMomentumTol * scale) << "d " << d << " friction " << friction;
    }
}

TEST(Dpm, TooLargeTimeStepIsRefused) {
  const auto p = make_packing(2, Boundary::walls, {10, 10, 0}, {5, 5}, {1.0});
  auto c = base_config(2, Boundary::walls, {10, 10, 0}, 0.8, 1.0 / kMinStepsPerContact);
  EXPECT_NO_THROW(make_simulation(c, p, {}));
  c.dt = 1.01 / kMinStepsPerContact;
  try {
    make_simulation(c, p, {});
    FAIL() << "dt > t_c / " << kMinStepsPerContact << " accepted";
  } catch (const InputError& err) {
    EXPECT_EQ(err.field(), "dt");
    EXPECT_NE(std::string(err.what()).find("contact_time"), std::string::npos);
  }
}

TEST(Dpm, SwitchedOffEffectsDoNoWork) {
  std::vector<double> vel;
  const auto p = gas(2, 8, 2.2, 1.0, vel, 0.5, kDpmSeed);
  auto c = base_config(2, Boundary::periodic, p.box, 0.7, 1.0 / 20);
  auto plain = make_simulation(c, p, vel);
  plain->run(200);
  EXPECT_GT(plain->stats().pair_contacts, 0u);
  EXPECT_EQ(plain->stats().friction_evaluations, 0u);
  EXPECT_EQ(plain->stats().gravity_evaluations, 0u);
  c.friction = true;
  c.gravity = true;
  c.g = {0, -0.01, 0};
  auto full = make_simulation(c, p, vel);
  full->run(200);
  EXPECT_EQ(full->stats().friction_evaluations, full->stats().pair_contacts);
  EXPECT_EQ(full->stats().gravity_evaluations, (200u + 1) * p.size());  // + the initial forces
}

TEST(Dpm, FreeFallUnderGravityIsExact) {
  const auto p = make_packing(2, Boundary::walls, {10, 100, 0}, {5, 90}, {1.0});
  auto c = base_config(2, Boundary::walls, {10, 100, 0}, 0.8, 0.05);
  c.gravity = true;
  c.g = {0, -1, 0};
  auto sim = make_simulation(c, p, {});
  sim->run(100);  // t = 5: y = 90 - 12.5
  EXPECT_NEAR(sim->positions()[1], 90 - 0.5 * 25, 1e-9);
  EXPECT_NEAR(sim->velocities()[1], -5, 1e-12);
}

// The trajectory is a property of the scene, not of the contact detection:
// forces are summed in the same order whatever grid (sizes, levels, search
// direction) found the contacts, so a run with the optimal grid and one with
// the linked cell are the same simulation, bit for bit.
TEST(Dpm, TrajectoryDoesNotDependOnTheGrid) {
  for (int d : {2, 3})
    for (bool friction : {false, true}) {
      std::vector<double> vel;
      const auto p = gas(d, d == 2 ? 12 : 5, 2.05, 1.0, vel, 0.5, kDpmSeed + 7 * d);
      SCOPED_TRACE("seed " + std::to_string(kDpmSeed + 7 * d) + ", d " + std::to_string(d) + ", friction " +
                   std::to_string(friction));
      auto c = base_config(d, Boundary::periodic, p.box, 0.7, 1.0 / 20);
      c.friction = friction;
      std::vector<std::vector<double>> runs;
      std::uint64_t contacts = 0;
      for (auto [sizes, search] : {std::pair{std::vector<double>{2.5}, Search::top_down},
                                   std::pair{std::vector<double>{1.25, 2.5}, Search::top_down},
                                   std::pair{std::vector<double>{1.25, 2.5}, Search::bottom_up},
                                   std::pair{std::vector<double>{1.2, 1.6, 2.2}, Search::top_down}}) {
        c.sizes = sizes;
        c.search = search;
        auto sim = make_simulation(c, p, vel);
        sim->run(2000);
        contacts = sim->stats().pair_contacts;
        auto x = sim->positions();
        const auto v = sim->velocities();
        x.insert(x.end(), v.begin(), v.end());
        runs.push_back(std::move(x));
      }
      // A contact list with a skin: rebuilt far less often, the same trajectory.
      for (const double skin : {0.3, 1.0}) {
        c.sizes = {1.25, 2.5};
        c.search = Search::bottom_up;
        c.skin = skin;
        auto sim = make_simulation(c, p, vel);
        sim->run(2000);
        EXPECT_LT(sim->stats().list_builds, 2000u / 4) << "skin " << skin;
        EXPECT_EQ(sim->stats().pair_contacts, contacts) << "skin " << skin;
        auto x = sim->positions();
        const auto v = sim->velocities();
        x.insert(x.end(), v.begin(), v.end());
        runs.push_back(std::move(x));
      }
      c.skin = 0;
      EXPECT_GT(contacts, 2000u);
      for (std::size_t k = 1; k < runs.size(); ++k) EXPECT_TRUE(runs[k] == runs[0]) << "grid " << k;
    }
}

// Contact detection on 1, 2, 3 and 8 threads: the same trajectory, bit for
// bit (the pairs are sorted into canonical order before the force sums).
TEST(Dpm, TrajectoryDoesNotDependOnTheThreads) {
  for (int d : {2, 3}) {
    std::vector<double> vel;
    const auto p = gas(d, d == 2 ? 40 : 12, 2.05, 1.0, vel, 0.5, kDpmSeed + 11 * d);
    SCOPED_TRACE("seed " + std::to_string(kDpmSeed + 11 * d) + ", d " + std::to_string(d));
    auto c = base_config(d, Boundary::periodic, p.box, 0.7, 1.0 / 20);
    c.sizes = {1.25, 2.5};
    std::vector<std::vector<double>> runs;
    for (int threads : {1, 2, 3, 8}) {
      c.threads = threads;
      auto sim = make_simulation(c, p, vel);
      sim->run(300);
      auto x = sim->positions();
      const auto v = sim->velocities();
      x.insert(x.end(), v.begin(), v.end());
      runs.push_back(std::move(x));
      EXPECT_GT(sim->stats().pair_contacts, 300u);
    }
    for (std::size_t k = 1; k < runs.size(); ++k) EXPECT_TRUE(runs[k] == runs[0]) << "threads run " << k;
  }
}

// The same with every force on: a dense, overlapping pile between walls, with
// friction and gravity (contacts, forces, torques and the integration all on
// the given number of threads; positions, velocities and counters equal bit
// for bit).
TEST(Dpm, DensePileWithFrictionDoesNotDependOnTheThreads) {
  for (int d : {2, 3}) {
    const std::uint64_t seed = kDpmSeed + 13 * d;
    SCOPED_TRACE("seed " + std::to_string(seed) + ", d " + std::to_string(d));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int per_axis = d == 2 ? 60 : 14;
    const double spacing = 1.6, a = per_axis * spacing;
    std::vector<double> pos, radii, vel;
    const int n = d == 2 ? per_axis * per_axis : per_axis * per_axis * per_axis;
    for (int i = 0; i < n; ++i) {
      int rest = i;
      for (int k = 0; k < d; ++k) {
        pos.push_back((rest % per_axis + 0.3 + 0.4 * u(rng)) * spacing);
        rest /= per_axis;
        vel.push_back(0.2 * (u(rng) - 0.5));
      }
      radii.push_back(0.6 + 0.4 * u(rng));  // overlaps its neighbours and the walls
    }
    const auto p = make_packing(d, Boundary::walls, {a, a, a}, pos, radii);
    auto c = base_config(d, Boundary::walls, p.box, 0.5, 1.0 / 20);
    c.contact_time = 0.5;
    c.dt = c.contact_time / 20;
    c.friction = true;
    c.gravity = true;
    c.g = {0.0, -0.05, 0.0};
    c.sizes = {1.3, 2.1};
    c.tangential = d == 2 ? TangentialLaw::spring : TangentialLaw::viscous;  // springs carried across rebuilds
    std::vector<std::vector<double>> runs;
    std::vector<std::array<std::uint64_t, 3>> counts;
    for (int threads : {1, 2, 3, 8}) {
      c.threads = threads;
      c.skin = threads % 2 == 0 ? 0.4 : 0.0;  // and the same with a contact list's skin
      auto sim = make_simulation(c, p, vel);
      sim->run(40);
      auto x = sim->positions();
      const auto v = sim->velocities();
      x.insert(x.end(), v.begin(), v.end());
      x.push_back(sim->kinetic_energy());  // includes the spins
      runs.push_back(std::move(x));
      const auto& st = sim->stats();
      counts.push_back({st.pair_contacts, st.wall_contacts, st.friction_evaluations});
    }
    EXPECT_GT(counts[0][0], 40u * static_cast<std::uint64_t>(n) / 2) << "dense: over half a contact per particle";
    EXPECT_GT(counts[0][1], 40u);
    for (std::size_t k = 1; k < runs.size(); ++k) {
      EXPECT_TRUE(runs[k] == runs[0]) << "threads run " << k;
      EXPECT_EQ(counts[k], counts[0]) << "threads run " << k;
    }
  }
}

}  // namespace
}  // namespace hgrid::dpm
