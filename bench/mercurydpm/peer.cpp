// MercuryDPM's HGrid as a contact-detection peer of `peers`: the particles
// of a packing (3D or 2D) in a Mercury3D/Mercury2D, its HGrid with the cell
// sizes given (USER distribution) or its own default (MercuryBase's
// constructor: 3 levels, EXPONENTIAL, cellOverSizeRatio 1), timed to find
// the contacts: one grid update (hGridActionsBeforeTimeStep, which a
// simulation runs every step) and one sweep of its broad phase, whose
// candidate pairs get the overlap test and nothing else
// (computeInternalForce overridden, as in free_cooling.cpp). A periodic
// packing gets MercuryDPM's PeriodicBoundary on every axis, and so its ghost
// particles (searched like the others, as in a simulation); "open" puts the
// same centres in a box without boundaries. A counting run of the same state
// collects the distinct pairs in contact (a ghost stands for its original).
//
// Usage: mercurydpm_peer FILE.xyz D SIZES|default periodic|open REPEATS
//   FILE.xyz: as `hgrid export --xyz` writes it (peers writes it); D: 2 or 3
// Prints one JSON object.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <unordered_set>
#include <vector>

#include "Boundaries/PeriodicBoundary.h"
#include "Mercury2D.h"
#include "Mercury3D.h"
#include "Particles/SphericalParticle.h"
#include "Species/LinearViscoelasticSpecies.h"
#include "xyz_input.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

[[noreturn]] void fail(const std::string& m) {
  std::fprintf(stderr, "mercurydpm_peer: %s\n", m.c_str());
  std::exit(2);
}

using Input = hgridlab_mercurydpm::XyzInput;

template <class Base>
class Peer : public Base {
 public:
  const Input* input = nullptr;
  bool periodic = true;
  std::vector<double> user_sizes;
  bool counting = false;
  std::uint64_t candidates = 0;
  std::unordered_set<std::uint64_t> pairs;

  Mdouble userHGridCellSize(unsigned int level) override { return user_sizes.at(level); }

  void setupInitialConditions() override {
    auto* species = this->speciesHandler.copyAndAddObject(LinearViscoelasticSpecies());
    species->setDensity(1.0);
    species->setStiffness(1.0);
    const int d = input->d;
    if (periodic)
      for (int a = 0; a < d; ++a) {
        PeriodicBoundary b;
        b.set(Vec3D(a == 0, a == 1, a == 2), 0.0, input->L[a]);
        this->boundaryHandler.copyAndAddObject(b);
      }
    SphericalParticle p;
    p.setSpecies(species);
    for (std::size_t i = 0; i < input->r.size(); ++i) {
      p.setRadius(input->r[i]);
      p.setPosition(Vec3D(input->x[i * d], input->x[i * d + 1], d == 3 ? input->x[i * d + 2] : 0.0));
      p.setVelocity(Vec3D(0, 0, 0));
      this->particleHandler.copyAndAddObject(p);
    }
  }

  std::vector<double> cell_sizes() { return this->getHGrid()->getCellSizes(); }

  /// One search as a step of MercuryDPM's (DPMBase::computeOneTimeStep)
  /// runs it: the ghosts of the periodic boundaries made, the grid updated,
  /// the broad phase over every particle (ghosts included), the ghosts
  /// removed again.
  double search() {
    candidates = 0;
    const auto t0 = Clock::now();
    this->checkAndDuplicatePeriodicParticles();
    this->hGridActionsBeforeTimeStep();
    Base::computeAllForces();
    with_ghosts = this->particleHandler.getSize();
    this->removeDuplicatePeriodicParticles();
    return since(t0);
  }
  std::size_t with_ghosts = 0;

 protected:
  void computeInternalForce(BaseParticle* a, BaseParticle* b) override {
    ++candidates;
    if (!counting) return;
    const Vec3D dx = a->getPosition() - b->getPosition();
    const Mdouble s = a->getRadius() + b->getRadius();
    if (dx.getLengthSquared() >= s * s) return;
    const auto id = [](BaseParticle* p) {
      while (p->getPeriodicFromParticle()) p = p->getPeriodicFromParticle();
      return static_cast<std::uint64_t>(p->getIndex());
    };
    std::uint64_t i = id(a), j = id(b);
    if (i > j) std::swap(i, j);
    if (i != j) pairs.insert(i << 32 | j);
  }
};

template <class Base>
int run(const Input& in, const std::string& grid, bool periodic, int repeats) {
  std::vector<double> sizes;
  if (grid != "default") {
    std::istringstream s(grid);
    for (std::string item; std::getline(s, item, ',');) sizes.push_back(std::atof(item.c_str()));
    if (sizes.empty()) fail("no cell sizes");
    // MercuryDPM inserts a particle on the first level whose cell exceeds its
    // diameter (HGrid::insertParticleToHgrid): the top size a hair larger.
    sizes.back() = std::nextafter(sizes.back(), 1e300) * (1 + 1e-12);
  }
  const auto setup = [&](Peer<Base>& w) {
    w.input = &in;
    w.periodic = periodic;
    w.user_sizes = sizes;
    w.setName("hgridlab_mercurydpm_peer");
    w.setFileType(FileType::NO_FILE);
    w.setSaveCount(1000000);
    w.setGravity(Vec3D(0, 0, 0));
    w.setDomain(Vec3D(0, 0, 0), Vec3D(in.L[0], in.L[1], in.d == 3 ? in.L[2] : 0.0));
    w.setTimeStep(1e-12);  // the particles stand still: one step builds the grid and the ghosts
    w.setTimeMax(0.5e-12);
    w.setHGridMethod(TOPDOWN);
    if (!sizes.empty()) {
      w.setHGridDistribution(USER);
      w.setHGridMaxLevels(static_cast<unsigned>(sizes.size()));
      w.setHGridCellOverSizeRatio(1.0);
    }
    w.setHGridUpdateEachTimeStep(true);
  };
  Peer<Base> timed;
  setup(timed);
  timed.solve();
  double best = 1e300;
  for (int k = 0; k < repeats; ++k) best = std::min(best, timed.search());
  Peer<Base> probe;
  setup(probe);
  probe.solve();
  probe.counting = true;
  probe.search();
  const std::vector<double> cells = timed.cell_sizes();
  std::printf("{\"grid\": \"%s\", \"boundary\": \"%s\", \"n\": %zu, \"particles_with_ghosts\": %zu, \"levels\": %zu, "
              "\"sizes\": [",
              grid == "default" ? "default" : "given", periodic ? "periodic" : "open", in.r.size(),
              timed.with_ghosts, cells.size());
  for (std::size_t l = 0; l < cells.size(); ++l) std::printf("%s%.9g", l ? ", " : "", cells[l]);
  std::printf("], \"seconds_per_build\": %.9f, \"repeats\": %d, \"candidates\": %llu, \"pairs\": %zu}\n", best, repeats,
              static_cast<unsigned long long>(probe.candidates), probe.pairs.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) fail("usage: mercurydpm_peer FILE.xyz D SIZES|default periodic|open REPEATS");
  const int d = std::atoi(argv[2]);
  if (d != 2 && d != 3) fail("D must be 2 or 3");
  const Input in = hgridlab_mercurydpm::read_xyz_input(argv[1], d);
  const std::string boundary = argv[4];
  if (boundary != "periodic" && boundary != "open") fail("boundary: periodic or open");
  const int repeats = std::atoi(argv[5]);
  if (repeats < 1) fail("REPEATS must be >= 1");
  // MercuryDPM's information messages go to stdout, which carries the JSON.
  static LoggerOutput quiet = *loggerOutput;
  quiet.onInfo = [](std::string, std::string, Flusher) {};
  quiet.onVerbose = [](std::string, std::string, Flusher) {};
  loggerOutput = &quiet;
  return in.d == 3 ? run<Mercury3D>(in, argv[3], boundary == "periodic", repeats)
                   : run<Mercury2D>(in, argv[3], boundary == "periodic", repeats);
}
