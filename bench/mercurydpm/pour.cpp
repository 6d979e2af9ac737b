// A polydisperse bed poured by MercuryDPM, for the density-field model's
// fixtures (tests/data/beds, beside the beds LAMMPS poured): N particles
// with diameters uniform in [DLO, DHI] are placed at random, without
// overlaps, in the upper part of a box walled on every side (3D: a column
// of side L; 2D: a slot of width L), and fall under gravity onto its floor.
// MercuryDPM writes its .data file (XBalls format, every snapshot in one
// file) at every SAVE time units; experiments/beds/make_mercurydpm_fixtures.sh
// keeps two snapshots (a gas over a forming bed, and the settled bed).
//   mercurydpm_pour OUTDIR NAME D N DLO DHI SEED
// Contact law: MercuryDPM's linear spring-dashpot with constant restitution
// (LinearViscoelasticSpecies, setConstantRestitution: every pair has
// collision time TC and restitution E, stiffness scaled by its effective
// mass), as the free-cooling driver (free_cooling.cpp). MercuryDPM's API as
// in Kernel/Walls/InfiniteWall.h, Kernel/Mercury3D.h and
// Drivers/MercurySimpleDemos of its source tree.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "Mercury2D.h"
#include "Mercury3D.h"
#include "Particles/SphericalParticle.h"
#include "Species/LinearViscoelasticSpecies.h"
#include "Walls/InfiniteWall.h"

namespace {

constexpr double kCollisionTime = 0.005;  // TC, gravity 1 and density 1
constexpr double kRestitution = 0.5;      // E
constexpr double kStepsPerCollision = 20;
constexpr double kFillFraction = 0.25;  // packing fraction of the placed cloud
constexpr double kSaveEvery = 2.0;      // time between snapshots
constexpr double kTimeMax = 24.0;

struct Setup {
  int d = 3;
  int n = 3000;
  double dlo = 0.2, dhi = 1.0;
  unsigned seed = 1;
  double side = 10;  // 3D: the column's side; 2D: the slot's width
  double height = 0;
};

/// Random non-overlapping centres and radii (largest first) in the region
/// [r, side - r] per horizontal axis, above `floor`.
struct Cloud {
  std::vector<std::array<double, 3>> x;
  std::vector<double> r;
};

Cloud place(const Setup& s, double floor, double top) {
  std::mt19937_64 rng(s.seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Cloud c;
  for (int i = 0; i < s.n; ++i) c.r.push_back(0.5 * (s.dlo + (s.dhi - s.dlo) * u(rng)));
  std::sort(c.r.rbegin(), c.r.rend());
  for (double r : c.r) {
    for (int attempt = 0;; ++attempt) {
      if (attempt > 100000) {
        std::fprintf(stderr, "mercurydpm_pour: could not place a particle of radius %g\n", r);
        std::exit(1);
      }
      std::array<double, 3> p{r + (s.side - 2 * r) * u(rng), 0, 0};
      if (s.d == 3) {
        p[1] = r + (s.side - 2 * r) * u(rng);
        p[2] = floor + r + (top - floor - 2 * r) * u(rng);
      } else {
        p[1] = floor + r + (top - floor - 2 * r) * u(rng);
      }
      bool free = true;
      for (std::size_t j = 0; j < c.x.size() && free; ++j) {
        double d2 = 0;
        for (int k = 0; k < s.d; ++k) d2 += (p[k] - c.x[j][k]) * (p[k] - c.x[j][k]);
        free = d2 >= (r + c.r[j]) * (r + c.r[j]);
      }
      if (free) {
        c.x.push_back(p);
        break;
      }
    }
  }
  return c;
}

template <class Base>
class Pour : public Base {
 public:
  Setup s;
  Cloud cloud;

  void setupInitialConditions() override {
    auto* species = this->speciesHandler.copyAndAddObject(LinearViscoelasticSpecies());
    species->setDensity(1.0);
    species->setConstantRestitution(true);  // before the collision time: per unit effective mass
    species->setCollisionTimeAndRestitutionCoefficient(kCollisionTime, kRestitution, 1.0);
    const int up = s.d == 3 ? 2 : 1;  // the vertical axis
    for (int k = 0; k < s.d; ++k) {
      Vec3D normal(0, 0, 0), lo(0, 0, 0), hi(0, 0, 0);
      normal.setComponent(k, 1.0);
      hi.setComponent(k, k == up ? s.height : s.side);
      InfiniteWall w;
      w.setSpecies(species);
      w.set(-normal, lo);
      this->wallHandler.copyAndAddObject(w);
      w.set(normal, hi);
      this->wallHandler.copyAndAddObject(w);
    }
    SphericalParticle p;
    p.setSpecies(species);
    for (std::size_t i = 0; i < cloud.r.size(); ++i) {
      p.setRadius(cloud.r[i]);
      p.setPosition(Vec3D(cloud.x[i][0], cloud.x[i][1], cloud.x[i][2]));
      p.setVelocity(Vec3D(0, 0, 0));
      this->particleHandler.copyAndAddObject(p);
    }
  }
};

template <class Base>
void run(const std::string& dir, const std::string& name, const Setup& setup) {
  Pour<Base> w;
  w.s = setup;
  // The cloud's height for kFillFraction, above a tenth of it kept clear.
  const double unit = setup.d == 3 ? M_PI / 6 : M_PI / 4;
  const double mean_dd = setup.d == 3
                             ? (std::pow(setup.dhi, 4) - std::pow(setup.dlo, 4)) / (4 * (setup.dhi - setup.dlo))
                             : (std::pow(setup.dhi, 3) - std::pow(setup.dlo, 3)) / (3 * (setup.dhi - setup.dlo));
  const double volume = setup.n * unit * mean_dd;
  const double base = setup.d == 3 ? setup.side * setup.side : setup.side;
  const double cloud_height = volume / (kFillFraction * base);
  const double floor = 0.1 * cloud_height;
  w.s.height = floor + cloud_height + setup.dhi;
  w.cloud = place(w.s, floor, floor + cloud_height);
  w.setName(dir + "/" + name);
  w.setSystemDimensions(setup.d);
  w.setParticleDimensions(setup.d);
  w.setDomain(Vec3D(0, 0, 0), Vec3D(setup.side, setup.d == 3 ? setup.side : w.s.height, setup.d == 3 ? w.s.height : 0.0));
  w.setGravity(setup.d == 3 ? Vec3D(0, 0, -1) : Vec3D(0, -1, 0));
  const double dt = kCollisionTime / kStepsPerCollision;
  w.setTimeStep(dt);
  w.setTimeMax(kTimeMax);
  w.setSaveCount(static_cast<unsigned>(std::lround(kSaveEvery / dt)));
  w.setFileType(FileType::ONE_FILE);
  w.restartFile.setFileType(FileType::NO_FILE);
  w.fStatFile.setFileType(FileType::NO_FILE);
  w.eneFile.setFileType(FileType::NO_FILE);
  w.setXBallsAdditionalArguments("");
  std::fprintf(stderr, "mercurydpm_pour: %s, %d particles, box %g x %g, %g time units (%ld steps)\n", name.c_str(),
               setup.n, setup.side, w.s.height, kTimeMax, std::lround(kTimeMax / dt));
  w.solve();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 8) {
    std::fprintf(stderr, "usage: %s OUTDIR NAME D N DLO DHI SEED\n", argv[0]);
    return 2;
  }
  Setup s;
  s.d = std::atoi(argv[3]);
  s.n = std::atoi(argv[4]);
  s.dlo = std::atof(argv[5]);
  s.dhi = std::atof(argv[6]);
  s.seed = static_cast<unsigned>(std::strtoul(argv[7], nullptr, 10));
  if (s.d != 2 && s.d != 3) {
    std::fprintf(stderr, "mercurydpm_pour: D must be 2 or 3\n");
    return 2;
  }
  if (!(s.n > 0 && s.dlo > 0 && s.dhi >= s.dlo)) {
    std::fprintf(stderr, "mercurydpm_pour: N must be > 0 and 0 < DLO <= DHI\n");
    return 2;
  }
  s.side = s.d == 3 ? 10 : 40;
  if (s.d == 3) run<Mercury3D>(argv[1], argv[2], s);
  else run<Mercury2D>(argv[1], argv[2], s);
  return 0;
}
