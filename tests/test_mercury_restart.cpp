// MercuryDPM's .restart files: what MercuryDPM wrote (tests/data/mercurydpm/)
// reads as the packing it simulated, and its pairs are those MercuryDPM's own
// contact detection listed; hand-made files for the layouts and the refusals.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/io/particle_file.hpp"
#include "hgridlab/measure/pairs.hpp"
#include "support.hpp"

namespace hgrid::test {
namespace {

const std::string kDir = std::string(HGRID_SOURCE_DIR) + "/tests/data/mercurydpm/";

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The particle pairs of the file's Interactions section (MercuryDPM's contacts).
std::set<Pair> mercury_contacts(const std::string& text) {
  std::set<Pair> out;
  std::stringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::string type, key;
    std::uint32_t i = 0, j = 0;
    if (ls >> type >> key >> i >> j && key == "particleIds") out.emplace(std::min(i, j), std::max(i, j));
  }
  return out;
}

std::set<Pair> our_pairs(const Packing& p, bool brute) {
  std::vector<std::vector<Pair>> per(2);  // one list per thread
  const auto add = [&](int t, std::uint32_t i, std::uint32_t j) { per[static_cast<std::size_t>(t)].emplace_back(i, j); };
  if (brute) for_each_packing_pair_brute(p, add);
  else for_each_packing_pair(p, GridParams{{2.0, 4.0}, Search::top_down, 2}, add);
  std::set<Pair> out;
  for (const auto& v : per)
    for (const Pair& q : v) EXPECT_TRUE(out.insert(q).second) << "a pair found twice";
  return out;
}

TEST(MercuryRestart, FilesMercuryWroteGiveItsContacts) {
  struct Case {
    const char* name;
    int d;
    Boundary boundary;
    double xy;
    std::size_t n;
  };
  for (const Case c : {Case{"periodic3d", 3, Boundary::periodic, 0.0, 60}, Case{"walls2d", 2, Boundary::walls, 0.0, 40},
                       Case{"leesedwards2d", 2, Boundary::periodic, 3.25, 40}}) {
    SCOPED_TRACE(c.name);
    const std::string path = kDir + c.name + ".restart";
    const ParticleSet s = read_particles(path);
    EXPECT_EQ(s.format, ParticleFormat::mercury_restart);
    const Packing p = read_packing(path);
    EXPECT_EQ(p.d, c.d);
    EXPECT_EQ(p.size(), c.n);
    EXPECT_EQ(p.boundary, c.boundary);
    EXPECT_EQ(p.tilt[0], c.xy);
    for (int a = 0; a < c.d; ++a) EXPECT_EQ(p.box[a], 20.0);
    const std::set<Pair> want = mercury_contacts(slurp(path));
    ASSERT_GT(want.size(), 10u);
    EXPECT_EQ(our_pairs(p, false), want);
    EXPECT_EQ(our_pairs(p, true), want);
    // The .data file of the same run: its last snapshot, the same radii.
    const Packing q = read_packing(kDir + c.name + ".data");
    ASSERT_EQ(q.size(), p.size());
    for (std::size_t i = 0; i < p.size(); ++i) EXPECT_NEAR(q.radii[i], p.radii[i], 1e-6 * p.radii[i]);
  }
}

/// A restart file of the current layout around the given boundary and
/// particle lines.
std::string restart(const std::string& version, const std::string& walls, const std::string& boundaries,
                    const std::string& particles, int d = 3) {
  return "MercuryDPM " + version + " name x revision  repository \n"
         "dataFile    fileType ONE_FILE saveCount 1 counter 3 lastSavedTimeStep 2\n"
         "xMin 0 xMax 10 yMin 0 yMax 10 zMin 0 zMax " + std::string(d == 3 ? "10" : "0") + "\n"
         "timeStep 0.0001 time 0.0002 ntimeSteps 2 timeMax 0.00015\n"
         "systemDimensions " + std::to_string(d) + " particleDimensions 3 gravity 0 0 0 backgroundDrag 0 random  0 1 2 3\n"
         "Species 1\nLinearViscoelasticSpecies id 0 density 1 stiffness 1000 dissipation 0\n" +
         walls + boundaries + particles + "Interactions 0\n";
}

const std::string kTwo =
    "Particles 2\n"
    "BaseParticle id 0 indSpecies 0 position 1 1 1 orientation 1 0 0 0 velocity 0 0 0 angularVelocity 0 0 0 "
    "force 0 0 0 torque 0 0 0 radius 0.5 invMass 1 timeStamp 0\n"
    "BaseParticle id 1 groupID 2 indSpecies 0 position 9.5 9.25 1 positionAbsolute 9.5 9.25 1 orientation 1 0 0 0 "
    "velocity 0 0 0 angularVelocity 0 0 0 force 0 0 0 torque 0 0 0 radius 1 invMass 1\n";

TEST(MercuryRestart, LayoutsAndBoundaries) {
  // Lees-Edwards in 3D with a periodic z: tilted xy, the shift reduced into [-lx/2, lx/2).
  const std::string le = "Boundaries 2\nLeesEdwardsBoundary id 0 left 0 right 10 down 0 up 10 shift 17 vel 0.5\n"
                         "PeriodicBoundary id 1 normal 0 0 1 scaleFactor 1 distanceLeft 0 distanceRight 10 shift 0 0 10\n";
  const Packing p = to_packing(parse_particles(restart("1.0", "Walls 0\n", le, kTwo), "le.restart"), "le.restart");
  EXPECT_EQ(p.boundary, Boundary::periodic);
  EXPECT_EQ(p.tilt, (std::array<double, 3>{-3, 0, 0}));
  // Periodic boundaries given by -e: the same slabs.
  const std::string neg = "Boundaries 3\n"
                          "PeriodicBoundary id 0 normal -1 0 0 scaleFactor 1 distanceLeft -10 distanceRight 0 shift -10 0 0\n"
                          "PeriodicBoundary id 1 normal 0 1 0 scaleFactor 1 distanceLeft 0 distanceRight 10 shift 0 10 0\n"
                          "TimeDependentPeriodicBoundary id 2 normal 0 0 1 distanceLeft 0 distanceRight 10\n";
  const Packing q = to_packing(parse_particles(restart("0.14", "Walls 0\n", neg, kTwo), "n.restart"), "n.restart");
  EXPECT_EQ(q.boundary, Boundary::periodic);
  EXPECT_FALSE(q.tilted());
  EXPECT_EQ(q.box, (std::array<double, 3>{10, 10, 10}));
  EXPECT_EQ(q.positions[3], 9.5);
  // No periodic boundary: walls, the box between the walls or the domain.
  const ParticleSet w = parse_particles(restart("1.0", "Walls 0\n", "Boundaries 0\n", kTwo, 2), "w.restart");
  EXPECT_EQ(w.d, 2);
  EXPECT_EQ(w.boundary, Boundary::walls);
  EXPECT_EQ(w.positions, (std::vector<double>{1, 1, 9.5, 9.25}));
  // Periodic x only: mixed, refused as a packing (one boundary for the grid).
  const std::string one = "Boundaries 1\n"
                          "PeriodicBoundary id 0 normal 1 0 0 scaleFactor 1 distanceLeft 0 distanceRight 10 shift 10 0 0\n";
  const ParticleSet m = parse_particles(restart("1.0", "Walls 0\n", one, kTwo), "m.restart");
  EXPECT_TRUE(m.mixed_boundary);
  EXPECT_THROW(to_packing(m, "m.restart"), InputError);
}

TEST(MercuryRestart, RefusalsNameTheFieldAndLine) {
  const auto field_of = [](const std::string& text) {
    try {
      parse_particles(text, "f.restart");
    } catch (const InputError& e) {
      return e.field() + " | " + e.what();
    }
    return std::string("accepted");
  };
  // The old flat layout.
  EXPECT_NE(field_of("restart_version 3 name x\n").find("restart_version"), std::string::npos);
  // Fewer particle lines than declared: at the line where they stop.
  std::string short_ = restart("1.0", "Walls 0\n", "Boundaries 0\n", kTwo);
  short_.replace(short_.find("Particles 2"), 11, "Particles 3");
  const std::string e = field_of(short_);
  EXPECT_NE(e.find("Particles"), std::string::npos) << e;
  EXPECT_NE(e.find("f.restart:13"), std::string::npos) << e;  // where the third should be
  // A boundary that is no box.
  EXPECT_NE(field_of(restart("1.0", "Walls 0\n",
                             "Boundaries 1\nAngledPeriodicBoundary id 0 normal_left 1 0 0 normal_right 0 1 0 origin 0 0 0\n",
                             kTwo))
                .find("Boundaries"),
            std::string::npos);
  // No Particles section.
  std::string none = restart("1.0", "Walls 0\n", "Boundaries 0\n", "");
  EXPECT_NE(field_of(none).find("Particles | "), std::string::npos) << field_of(none);
  // One rank's file of an MPI run.
  std::string mpi = restart("1.0", "Walls 0\n", "Boundaries 0\n", kTwo);
  mpi.replace(mpi.find("random  0 1 2 3"), 15, "random  0 1 2 3 numberOfProcessors 4 numberOfDomains 2 2 1");
  EXPECT_NE(field_of(mpi).find("numberOfProcessors"), std::string::npos);
  // A particle without radius.
  std::string nor = restart("1.0", "Walls 0\n", "Boundaries 0\n", kTwo);
  nor.replace(nor.find("radius 0.5"), 10, "");
  EXPECT_NE(field_of(nor).find("Particles"), std::string::npos);
}

}  // namespace
}  // namespace hgrid::test
