// Writes MercuryDPM's own .restart and .data files for hgridlab's reader
// tests (tests/data/mercurydpm/): three small seeded systems, each run for
// two time steps so that MercuryDPM writes its files as a simulation does.
//   periodic3d: Mercury3D, PeriodicBoundary on x, y and z
//   walls2d:    Mercury2D, four InfiniteWalls
//   leesedwards2d: Mercury2D, a LeesEdwardsBoundary with a shift of 3.25
// Usage: mercurydpm_write_restart OUTDIR. Each system also writes
// NAME.contacts: the pairs MercuryDPM's contact detection found in contact
// after the last step (its interaction handler's count).
// MercuryDPM's API as in Kernel/Boundaries/{PeriodicBoundary,LeesEdwardsBoundary}.h
// and Drivers/MercurySimpleDemos/FreeCoolingDemo.cpp of its source tree.
#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#include "Boundaries/LeesEdwardsBoundary.h"
#include "Boundaries/PeriodicBoundary.h"
#include "Mercury2D.h"
#include "Mercury3D.h"
#include "Particles/SphericalParticle.h"
#include "Species/LinearViscoelasticSpecies.h"
#include "Walls/InfiniteWall.h"

namespace {

enum class Kind { periodic3d, walls2d, leesedwards2d };

template <class Base>
class Writer : public Base {
 public:
  Kind kind = Kind::periodic3d;
  double L = 20;
  int n = 60;
  unsigned seed = 1;

  void setupInitialConditions() override {
    auto* species = this->speciesHandler.copyAndAddObject(LinearViscoelasticSpecies());
    species->setDensity(1.0);
    species->setStiffness(1e3);
    const bool three = kind == Kind::periodic3d;
    if (kind == Kind::periodic3d) {
      for (const Vec3D& e : {Vec3D(1, 0, 0), Vec3D(0, 1, 0), Vec3D(0, 0, 1)}) {
        PeriodicBoundary b;
        b.set(e, 0.0, L);
        this->boundaryHandler.copyAndAddObject(b);
      }
    } else if (kind == Kind::walls2d) {
      const Vec3D faces[4][2] = {{{-1, 0, 0}, {0, 0, 0}}, {{1, 0, 0}, {L, 0, 0}}, {{0, -1, 0}, {0, 0, 0}},
                                 {{0, 1, 0}, {0, L, 0}}};
      for (const auto& f : faces) {
        InfiniteWall w;
        w.setSpecies(species);
        w.set(f[0], f[1]);
        this->wallHandler.copyAndAddObject(w);
      }
    } else {
      LeesEdwardsBoundary b;
      b.set([](Mdouble) { return 3.25; }, [](Mdouble) { return 0.0; }, 0.0, L, 0.0, L);
      this->boundaryHandler.copyAndAddObject(b);
    }
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    SphericalParticle p;
    p.setSpecies(species);
    for (int i = 0; i < n; ++i) {
      p.setRadius(0.5 + 1.5 * u(rng));
      const double x = u(rng) * L, y = u(rng) * L, z = three ? u(rng) * L : 0.0;
      p.setPosition(Vec3D(x, y, z));
      p.setVelocity(Vec3D(0, 0, 0));
      this->particleHandler.copyAndAddObject(p);
    }
  }
};

template <class Base>
void run(const std::string& dir, const std::string& name, Kind kind, int n, unsigned seed) {
  Writer<Base> w;
  w.kind = kind;
  w.n = n;
  w.seed = seed;
  w.setName(dir + "/" + name);
  w.setSystemDimensions(kind == Kind::periodic3d ? 3 : 2);
  w.setParticleDimensions(kind == Kind::periodic3d ? 3 : 2);
  w.setDomain(Vec3D(0, 0, 0), Vec3D(w.L, w.L, kind == Kind::periodic3d ? w.L : 0.0));
  w.setGravity(Vec3D(0, 0, 0));
  w.setTimeStep(1e-4);
  w.setTimeMax(1.5e-4);  // two steps
  w.setSaveCount(1);
  w.setFileType(FileType::ONE_FILE);
  w.fStatFile.setFileType(FileType::NO_FILE);
  w.eneFile.setFileType(FileType::NO_FILE);
  w.setXBallsAdditionalArguments("");
  w.solve();
  std::ofstream(dir + "/" + name + ".contacts") << w.interactionHandler.getNumberOfObjects() << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  run<Mercury3D>(dir, "periodic3d", Kind::periodic3d, 60, 1);
  run<Mercury2D>(dir, "walls2d", Kind::walls2d, 40, 2);
  run<Mercury2D>(dir, "leesedwards2d", Kind::leesedwards2d, 40, 3);
  return 0;
}
