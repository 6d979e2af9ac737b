// The paper's DPM free-cooling test (Krijgsman, Ogarko & Luding 2014, Sect. 5)
// run in MercuryDPM, the authors' own code, with its HGrid at given cell sizes
// (USER distribution), at one level (the linked cell) or at MercuryDPM's
// default choice; built against a MercuryDPM kernel by bench/mercurydpm/build.sh.
//
// The system is hgridlab's experiments/dpm_free_cooling.toml: the discs and box
// of an extended-XYZ file that `hgrid export --xyz` wrote from the scene's own
// packing, walls at the box faces, the scene's Gaussian initial velocities
// (the same generator and seed), no gravity, no friction, and MercuryDPM's linear
// spring-dashpot with constant restitution (setConstantRestitution: stiffness
// and dissipation per unit of the pair's effective mass, so every pair has
// the same contact time and restitution, as hgridlab's dpm/contact_law.hpp).
// MercuryDPM API followed from its Kernel (Mercury2D.h, MercuryBase.h:
// HGridDistribution USER and userHGridCellSize; HGrid.cc: a particle goes to the
// first level whose cell is larger than its diameter; Species/NormalForceSpecies/
// LinearViscoelasticNormalSpecies.cc) and its demo Drivers/MercurySimpleDemos/
// FreeCooling2DinWalls.cpp.
//
// Prints one JSON object: the grid used; the search of the initial state
// without forces (its wall time, cell accesses and candidate pairs: what fits
// MercuryDPM's K); then, for STEPS > 0, wall times (whole run; the forces loop,
// which holds contact detection and contact forces; one search of the final
// state), candidate pairs, and the kinetic energy every `sample_every` steps.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "Mercury2D.h"
#include "Particles/SphericalParticle.h"
#include "Species/LinearViscoelasticSpecies.h"
#include "Walls/InfiniteWall.h"
#include "xyz_input.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct Disc {
  double x, y, r;
};

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "free_cooling: %s\n", what.c_str());
  std::exit(2);
}

/// The discs and the box of an extended-XYZ file written by `hgrid export --xyz`.
std::vector<Disc> read_xyz(const std::string& path, double& lx, double& ly) {
  const hgridlab_mercurydpm::XyzInput in = hgridlab_mercurydpm::read_xyz_input(path, 2);
  lx = in.L[0], ly = in.L[1];
  std::vector<Disc> out(in.r.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = Disc{in.x[2 * i], in.x[2 * i + 1], in.r[i]};
  return out;
}

class FreeCooling : public Mercury2D {
 public:
  std::vector<Disc> discs;
  double lx = 0, ly = 0;
  double contact_time = 0.05, restitution = 0.8, density = 1.0, speed = 1.0;
  unsigned velocity_seed = 1;
  unsigned sample_every = 200;
  std::vector<double> user_sizes;  // empty: MercuryDPM's own distribution
  bool search_only = false;        // computeInternalForce counts candidate pairs instead
  std::uint64_t candidates = 0, overlaps = 0;
  double seconds_forces = 0;
  std::vector<double> t, E;

  Mdouble userHGridCellSize(unsigned int level) override { return user_sizes.at(level); }

  void setupInitialConditions() override {
    auto* species = speciesHandler.copyAndAddObject(LinearViscoelasticSpecies());
    species->setDensity(density);
    species->setConstantRestitution(true);  // before the collision time: per unit effective mass
    species->setCollisionTimeAndRestitutionCoefficient(contact_time, restitution, 1.0);
    const Vec3D faces[4][2] = {{{-1, 0, 0}, {0, 0, 0}}, {{1, 0, 0}, {lx, 0, 0}}, {{0, -1, 0}, {0, 0, 0}},
                               {{0, 1, 0}, {0, ly, 0}}};
    for (const auto& f : faces) {
      InfiniteWall w;
      w.setSpecies(species);
      w.set(f[0], f[1]);
      wallHandler.copyAndAddObject(w);
    }
    // The velocities hgridlab's scene draws (dpm_scene.cpp): the same
    // generator and seed, components in particle order, x then y.
    std::mt19937_64 rng(velocity_seed);
    std::normal_distribution<double> g(0.0, speed);
    SphericalParticle p;
    p.setSpecies(species);
    for (const Disc& d : discs) {
      const double vx = g(rng);
      const double vy = g(rng);
      p.setRadius(d.r);
      p.setPosition(Vec3D(d.x, d.y, 0));
      p.setVelocity(Vec3D(vx, vy, 0));
      particleHandler.copyAndAddObject(p);
    }
  }

  /// The cell sizes of the HGrid as built.
  std::vector<double> cell_sizes() { return getHGrid()->getCellSizes(); }

  /// One search of the current state (no forces): candidate pairs, each
  /// tested for overlap as MercuryDPM's narrow phase does, and counted.
  double time_search() {
    search_only = true;
    candidates = overlaps = 0;
    const auto t0 = Clock::now();
    Mercury2D::computeAllForces();
    const double s = since(t0);
    search_only = false;
    return s;
  }

 protected:
  void computeAllForces() override {
    const auto t0 = Clock::now();
    Mercury2D::computeAllForces();
    seconds_forces += since(t0);
  }

  void computeInternalForce(BaseParticle* a, BaseParticle* b) override {
    if (search_only) {  // the narrow phase's overlap test, no interaction, no force
      ++candidates;
      const Vec3D d = a->getPosition() - b->getPosition();
      const Mdouble r = a->getRadius() + b->getRadius();
      overlaps += d.getLengthSquared() < r * r;
      return;
    }
    Mercury2D::computeInternalForce(a, b);
  }

  void actionsAfterTimeStep() override {
    if (getNumberOfTimeSteps() % sample_every == 0) {
      t.push_back(getTime());
      E.push_back(getKineticEnergy());
    }
  }
};

/// The same run counting MercuryDPM's cell accesses (every cell a search
/// looks into: MercuryDPM's hGridFindContactsWith(in)TargetCell calls), for
/// the counts alone: its overrides cost time, so the timings come from a
/// FreeCooling of the same state.
class CountingProbe : public FreeCooling {
 public:
  std::uint64_t accesses = 0;

 protected:
  void hGridFindContactsWithinTargetCell(int x, int y, unsigned int l) override {
    ++accesses;
    FreeCooling::hGridFindContactsWithinTargetCell(x, y, l);
  }
  void hGridFindContactsWithTargetCell(int x, int y, unsigned int l, BaseParticle* obj) override {
    ++accesses;
    FreeCooling::hGridFindContactsWithTargetCell(x, y, l, obj);
  }
};

std::vector<double> parse_sizes(const std::string& s) {
  std::vector<double> out;
  std::istringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::atof(item.c_str()));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5)
    fail("usage: free_cooling FILE.xyz STEPS SIZES|default SAMPLE_EVERY [contact_time restitution dt_over_tc speed "
         "velocity_seed]\n  SIZES: cell sizes s1,...,sL in the file's unit (one size: the linked cell); default: "
         "MercuryDPM's own HGrid; STEPS 0: the initial state's search alone");
  std::vector<Disc> discs;
  double lx = 0, ly = 0;
  discs = read_xyz(argv[1], lx, ly);
  const long steps = std::atol(argv[2]);
  const std::string grid = argv[3];
  const long sample_every = std::atol(argv[4]);
  double contact_time = 0.05, restitution = 0.8, dt_over_tc = 0.05, speed = 1.0;
  unsigned velocity_seed = 1;
  if (argc > 5) contact_time = std::atof(argv[5]);
  if (argc > 6) restitution = std::atof(argv[6]);
  if (argc > 7) dt_over_tc = std::atof(argv[7]);
  if (argc > 8) speed = std::atof(argv[8]);
  if (argc > 9) velocity_seed = static_cast<unsigned>(std::atol(argv[9]));
  if (steps < 0 || sample_every < 1) fail("STEPS must be >= 0 and SAMPLE_EVERY >= 1");
  std::vector<double> user_sizes;
  if (grid != "default") {
    user_sizes = parse_sizes(grid);
    if (user_sizes.empty()) fail("no cell sizes");
    // MercuryDPM puts a particle in the first level whose cell is larger than
    // its diameter (HGrid::insertParticleToHgrid): the largest disc, whose
    // diameter equals the top size, needs a top cell a hair larger.
    user_sizes.back() = std::nextafter(user_sizes.back(), 1e300) * (1 + 1e-12);
  }
  // MercuryDPM's information messages go to stdout, which carries the JSON:
  // dropped (warnings and errors stay).
  static LoggerOutput quiet = *loggerOutput;
  quiet.onInfo = [](std::string, std::string, Flusher) {};
  quiet.onVerbose = [](std::string, std::string, Flusher) {};
  loggerOutput = &quiet;

  const double dt = dt_over_tc * contact_time;
  // A run of n_steps steps.
  const auto setup = [&](FreeCooling& run, long n_steps) {
    run.discs = discs;
    run.lx = lx, run.ly = ly;
    run.contact_time = contact_time, run.restitution = restitution, run.speed = speed;
    run.velocity_seed = velocity_seed;
    run.sample_every = static_cast<unsigned>(sample_every);
    run.user_sizes = user_sizes;
    run.setName("hgridlab_free_cooling");
    run.setFileType(FileType::NO_FILE);
    run.setSaveCount(static_cast<unsigned>(n_steps) + 1);
    run.setGravity(Vec3D(0, 0, 0));
    run.setDomain(Vec3D(0, 0, 0), Vec3D(lx, ly, 0));
    run.setTimeStep(dt);
    run.setTimeMax((static_cast<double>(n_steps) - 0.5) * dt);
    run.setHGridMethod(TOPDOWN);
    run.setHGridCellOverSizeRatio(1.0);
    if (!user_sizes.empty()) {
      run.setHGridDistribution(USER);
      run.setHGridMaxLevels(static_cast<unsigned>(user_sizes.size()));
    }
    run.setHGridUpdateEachTimeStep(true);
  };
  // The search of the initial state (after one step: MercuryDPM builds its
  // grid in the step): fastest of 5 uncounted, and the counts (cell
  // accesses, candidate pairs) of a counting probe of the same state.
  FreeCooling first;
  setup(first, 1);
  first.solve();
  double search_initial = 1e300;
  for (int k = 0; k < 5; ++k) search_initial = std::min(search_initial, first.time_search());
  CountingProbe probe;
  setup(probe, 1);
  probe.solve();
  probe.accesses = 0;
  probe.time_search();

  FreeCooling run;
  double seconds_total = 0, best_search = 0;
  if (steps > 0) {
    setup(run, steps);
    const auto t0 = Clock::now();
    run.solve();
    seconds_total = since(t0);
    // One search of the final state without forces, several times (fastest):
    // contact detection alone, as hgridlab's query.
    best_search = 1e300;
    for (int k = 0; k < 5; ++k) best_search = std::min(best_search, run.time_search());
  }
  const std::vector<double> cells = first.cell_sizes();
  std::printf("{\"grid\": \"%s\", \"levels\": %zu, \"sizes\": [", grid.c_str(), cells.size());
  for (std::size_t l = 0; l < cells.size(); ++l) std::printf("%s%.9g", l ? ", " : "", cells[l]);
  std::printf("], \"n\": %zu, \"steps\": %ld, \"dt\": %.9g, \"seconds_search_initial_state\": %.9f, "
              "\"cell_accesses_initial_state\": %llu, \"candidates_initial_state\": %llu",
              discs.size(), steps, dt, search_initial, static_cast<unsigned long long>(probe.accesses),
              static_cast<unsigned long long>(probe.candidates));
  if (steps > 0) {
    std::printf(", \"seconds_total\": %.6f, \"seconds_forces_loop\": %.6f, \"seconds_search_final_state\": %.9f, "
                "\"candidates_final_state\": %llu, \"t\": [",
                seconds_total, run.seconds_forces, best_search, static_cast<unsigned long long>(run.candidates));
    for (std::size_t i = 0; i < run.t.size(); ++i) std::printf("%s%.6g", i ? ", " : "", run.t[i]);
    std::printf("], \"E\": [");
    for (std::size_t i = 0; i < run.E.size(); ++i) std::printf("%s%.10g", i ? ", " : "", run.E[i]);
    std::printf("]");
  }
  std::printf("}\n");
  return 0;
}
