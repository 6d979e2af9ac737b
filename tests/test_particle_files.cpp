// Particle files in every text format (io/particle_file.hpp): named columns in
// any order, the plain layouts, LAMMPS data and dump files; malformed input
// refused naming the field and the line; mutated files never crash a reader.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/io/lammps_export.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/io/particle_file.hpp"
#include "support.hpp"

namespace hgrid::test {
namespace {

using ParticleFiles = TempDir;

std::string num(double v) { return format_number(v); }

/// A seeded periodic 3D packing (random centres, power-law radii).
Packing sample_packing(std::size_t n, std::uint64_t seed, Boundary b = Boundary::periodic) {
  return packing_from(random_scene<3>(n, 0.3, -3, 10, b, seed), b);
}

/// The same particles as each text format writes them (17 digits).
std::string as_csv(const Packing& p) {
  std::string t = "# box " + num(p.box[0]) + " " + num(p.box[1]) + " " + num(p.box[2]) + "\nx,y,z,r\n";
  for (std::size_t i = 0; i < p.size(); ++i)
    t += num(p.positions[3 * i]) + "," + num(p.positions[3 * i + 1]) + "," + num(p.positions[3 * i + 2]) + "," +
         num(p.radii[i]) + "\n";
  return t;
}
std::string as_text_with_diameters(const Packing& p) {
  std::string t = "# box " + num(p.box[0]) + " " + num(p.box[1]) + " " + num(p.box[2]) + "\nID Diameter vx Z Y X\n";
  for (std::size_t i = 0; i < p.size(); ++i)
    t += std::to_string(i) + "\t" + num(2 * p.radii[i]) + " 0 " + num(p.positions[3 * i + 2]) + " " +
         num(p.positions[3 * i + 1]) + " " + num(p.positions[3 * i]) + "\n";
  return t;
}
std::string as_dump(const Packing& p, bool scaled) {
  std::string t = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n" + std::to_string(p.size()) +
                  "\nITEM: BOX BOUNDS pp pp pp\n";
  for (int a = 0; a < 3; ++a) t += "0 " + num(p.box[a]) + "\n";
  t += scaled ? "ITEM: ATOMS id type xs ys zs diameter\n" : "ITEM: ATOMS id radius type z x y\n";
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double* x = &p.positions[3 * i];
    t += std::to_string(i + 1) + " ";
    t += scaled ? "1 " + num(x[0] / p.box[0]) + " " + num(x[1] / p.box[1]) + " " + num(x[2] / p.box[2]) + " " +
                      num(2 * p.radii[i])
                : num(p.radii[i]) + " 1 " + num(x[2]) + " " + num(x[0]) + " " + num(x[1]);
    t += "\n";
  }
  return t;
}

TEST_F(ParticleFiles, NamedColumnsInAnyOrderCaseAndUnitsIgnored) {
  const ParticleSet a = parse_particles("id,type,Radius [m],vx,X,y,z\n1,1,0.5,0,1,2,3\n2,1,0.25,9,4,5,6\n", "a.csv");
  EXPECT_EQ(a.format, ParticleFormat::table);
  EXPECT_EQ(a.d, 3);
  EXPECT_EQ(a.radii, (std::vector<double>{0.5, 0.25}));
  EXPECT_EQ(a.positions, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_FALSE(a.box);
  EXPECT_FALSE(a.boundary);
  const ParticleSet b = parse_particles("# box 10 20\n# boundary walls\n diam  pos_y pos_x\n1 2 3\n0.5 4 5\n", "b.txt");
  EXPECT_EQ(b.d, 2);
  EXPECT_EQ(b.radii, (std::vector<double>{0.5, 0.25}));
  EXPECT_EQ(b.positions, (std::vector<double>{3, 2, 5, 4}));
  ASSERT_TRUE(b.box);
  EXPECT_EQ((*b.box)[1], 20);
  EXPECT_EQ(b.boundary, Boundary::walls);
  const ParticleSet c = parse_particles("x;y;r\n1;2;0.5\n", "c.csv");  // semicolons
  EXPECT_EQ(c.radii, std::vector<double>{0.5});
  const ParticleSet r = parse_particles("id radius\n7 0.5\n8 2\n", "r.txt");  // radii only
  EXPECT_EQ(r.d, 0);
  EXPECT_FALSE(r.has_positions());
  EXPECT_EQ(r.radii, (std::vector<double>{0.5, 2}));
}

TEST_F(ParticleFiles, PlainLayoutsAndCommentedHeaders) {
  EXPECT_EQ(parse_particles("0.5\n1\n\n2e-3\n", "r.txt").radii, (std::vector<double>{0.5, 1, 2e-3}));
  const ParticleSet xy = parse_particles("# a comment\n1 2 0.5\n3 4 0.25\n", "xy.txt");
  EXPECT_EQ(xy.d, 2);
  EXPECT_EQ(xy.positions, (std::vector<double>{1, 2, 3, 4}));
  EXPECT_EQ(parse_particles("1 2 3 0.5\r\n", "xyz.txt").d, 3);  // CRLF
  const ParticleSet yade = parse_particles("#format x_y_z_r\n1 2 3 0.5\n", "yade.txt");
  EXPECT_EQ(yade.radii, std::vector<double>{0.5});
  const ParticleSet hashed = parse_particles("# id x y z d\n1 1 2 3 0.5\n", "hashed.txt");
  EXPECT_EQ(hashed.radii, std::vector<double>{0.25});
  EXPECT_EQ(hashed.positions, (std::vector<double>{1, 2, 3}));
  const ParticleSet prose = parse_particles("# d is the diameter\n1 2 0.5\n", "prose.txt");  // not a header
  EXPECT_EQ(prose.radii, std::vector<double>{0.5});
  EXPECT_EQ(prose.d, 2);
}

TEST_F(ParticleFiles, LammpsDataFilesAsExportWritesThemAndByHand) {
  Packing p = sample_packing(50, 3);
  const ParticleSet s = parse_particles(lammps_data(p), "data.lmp");
  EXPECT_EQ(s.format, ParticleFormat::lammps_data);
  EXPECT_EQ(s.d, 3);
  EXPECT_EQ(s.radii, p.radii);
  EXPECT_EQ(s.positions, p.positions);
  EXPECT_EQ(*s.box, p.box);
  EXPECT_FALSE(s.boundary);  // a data file does not say
  EXPECT_EQ(boundary_description(s), "periodic (not in the file: assumed)");
  // 2D as LAMMPS keeps it: z = 0 in a box around it.
  Packing q;
  q.d = 2, q.box = {4, 5, 0}, q.positions = {1, 1, 3, 4}, q.radii = {0.5, 0.25};
  const ParticleSet s2 = parse_particles(lammps_data(q), "2d.lmp");
  EXPECT_EQ(s2.d, 2);
  EXPECT_EQ(s2.positions, q.positions);
  EXPECT_EQ((*s2.box)[1], 5);
  // By hand: comments, other sections, image flags, a shifted box.
  const std::string hand =
      "my title\n\n2 atoms # two\n1 atom types\n-1 1 xlo xhi\n-2 2 ylo yhi\n0 1 zlo zhi\n\nMasses\n\n1 1.0\n\n"
      "Atoms # sphere\n\n1 1 0.5 1.0 0 0 0.5 0 0 0\n2 1 0.25 1.0 0.5 1 0.75 1 0 0 # last\n\nVelocities\n\n1 0 0 0 0 0 0\n";
  const ParticleSet h = parse_particles(hand, "hand.data");
  EXPECT_EQ(h.radii, (std::vector<double>{0.25, 0.125}));
  EXPECT_EQ(h.positions, (std::vector<double>{1, 2, 0.5, 1.5, 3, 0.75}));
  EXPECT_EQ(*h.box, (std::array<double, 3>{2, 4, 1}));
  // A 2D run's write_data: every z = 0 in zlo zhi = 0 1 (not around 0),
  // and the tilts of a triclinic box that has none: 2D, orthogonal.
  const std::string flat =
      "LAMMPS data file via write_data\n\n2 atoms\n1 atom types\n\n0 10 xlo xhi\n0 8 ylo yhi\n0 1 zlo zhi\n"
      "0 0 0 xy xz yz\n\nAtoms # sphere\n\n1 1 1 1 2 3 0 0 0 0\n2 1 2 1 6 5 0 0 0 0\n";
  const ParticleSet f = parse_particles(flat, "flat.data");
  EXPECT_EQ(f.d, 2);
  EXPECT_EQ(f.positions, (std::vector<double>{2, 3, 6, 5}));
  EXPECT_EQ((*f.box)[0], 10);
  EXPECT_EQ((*f.box)[1], 8);
}

TEST_F(ParticleFiles, LammpsDumpFilesFirstSnapshotAnyColumns) {
  Packing p = sample_packing(40, 4);
  for (bool scaled : {false, true}) {
    const std::string two = as_dump(p, scaled) + as_dump(sample_packing(40, 5), false);
    // The last snapshot unless asked; --frame from the first or the end.
    EXPECT_EQ(parse_particles(two, "a.dump").radii, sample_packing(40, 5).radii);
    EXPECT_EQ(parse_particles(two, "a.dump", -1).radii, sample_packing(40, 5).radii);
    EXPECT_EQ(parse_particles(two, "a.dump", -2).radii, p.radii);
    EXPECT_THROW(parse_particles(two, "a.dump", 2), InputError);
    EXPECT_THROW(parse_particles(two, "a.dump", -3), InputError);
    const ParticleSet s = parse_particles(two, "a.dump", 0);
    EXPECT_EQ(s.frame, 0u);
    EXPECT_EQ(s.frames, 2u);
    EXPECT_EQ(s.format, ParticleFormat::lammps_dump);
    EXPECT_EQ(s.radii, p.radii);
    EXPECT_EQ(s.boundary, Boundary::periodic);
    ASSERT_EQ(s.positions.size(), p.positions.size());
    for (std::size_t i = 0; i < p.positions.size(); ++i)
      EXPECT_NEAR(s.positions[i], p.positions[i], scaled ? 1e-12 * p.box[0] : 0.0);
  }
  const std::string walls = "ITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n0 2\n0 2\n0 2\nITEM: ATOMS x y z radius\n1 1 1 0.5\n";
  EXPECT_EQ(parse_particles(walls, "w.dump").boundary, Boundary::walls);
  // The header of a triclinic box without tilt: the orthogonal box.
  const ParticleSet t = parse_particles("ITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS xy xz yz pp pp pp\n0 2 0\n0 3 0\n"
                                        "0 4 0\nITEM: ATOMS x y z radius\n1 1 1 0.5\n0.5 0.5 2 0.25\n",
                                        "t.dump");
  EXPECT_EQ(t.d, 3);
  EXPECT_EQ(*t.box, (std::array<double, 3>{2, 3, 4}));
  EXPECT_EQ(t.boundary, Boundary::periodic);
  std::string mixed = walls;
  mixed.replace(mixed.find("ff ff ff"), 8, "pp pp fm");
  const ParticleSet m = parse_particles(mixed, "m.dump");
  EXPECT_TRUE(m.mixed_boundary);
  EXPECT_THROW(to_packing(m, "m.dump"), InputError);
}

// MercuryDPM's .data files (docs/record/MERCURYDPM_FILES.md): snapshots one after
// another, the first often empty; the last unless --frame says; 3D and 2D
// lines; the domain is the box, origin at its lower corner; no boundary.
TEST_F(ParticleFiles, MercuryDpmDataFilesAnySnapshot) {
  const std::string three =
      "0 0 0 0 0 10 10 10 \n"
      "2 0.5 0 0 0 10 10 10 \n1 2 3 0 0 0 0.5 0 0 0 0 0 0 0\n4 5 6 0.1 0 0 0.25 0 0 0 0 0 0 1\n"
      "2 1 0 0 0 10 10 10 \n1.5 2 3 0 0 0 0.5 0 0 0 0 0 0 0\n4 5.5 6 0.1 0 0 0.25 0 0 0 0 0 0 1\n";
  const ParticleSet s = parse_particles(three, "m.data");
  EXPECT_EQ(s.format, ParticleFormat::mercury_data);
  EXPECT_EQ(s.d, 3);
  EXPECT_EQ(s.frame, 2u);
  EXPECT_EQ(s.frames, 3u);
  EXPECT_EQ(s.radii, (std::vector<double>{0.5, 0.25}));
  EXPECT_EQ(s.positions, (std::vector<double>{1.5, 2, 3, 4, 5.5, 6}));
  EXPECT_EQ(*s.box, (std::array<double, 3>{10, 10, 10}));
  EXPECT_FALSE(s.boundary);
  EXPECT_EQ(parse_particles(three, "m.data", 1).positions, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(parse_particles(three, "m.data", -2).positions, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  for (const std::int64_t bad : {0, 3, -4}) {  // the empty first snapshot, and beyond the file
    try {
      parse_particles(three, "m.data", bad);
      ADD_FAILURE() << "frame " << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "frame") << e.what();
    }
  }
  // 2D: "N t xmin ymin xmax ymax", particles "x y vx vy r angle omega info".
  const ParticleSet t = parse_particles("2 0 -1 -1 9 9\n0 0 0 0 1 0 0 0\n4 4 0 0 0.5 0 0 0\n", "m2.data");
  EXPECT_EQ(t.d, 2);
  EXPECT_EQ(t.positions, (std::vector<double>{1, 1, 5, 5}));
  EXPECT_EQ(t.radii, (std::vector<double>{1, 0.5}));
  EXPECT_EQ((*t.box)[0], 10);
  EXPECT_EQ((*t.box)[1], 10);
  EXPECT_NEAR(t.packing_fraction(), std::acos(-1.0) * 1.25 / 100, 1e-15);
  // One snapshot in the other formats: --frame 0 or -1 only.
  EXPECT_NO_THROW(parse_particles("x y z r\n1 1 1 0.5\n", "t.txt", -1));
  EXPECT_THROW(parse_particles("x y z r\n1 1 1 0.5\n", "t.txt", 1), InputError);
  // From a file, through the command line.
  std::ofstream(path("run.data")) << three;
  const Result r = hgrid_run("recommend " + path("run.data") + " --frame 1 --json");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"n\": 2"), std::string::npos) << r.out;
  EXPECT_EQ(hgrid_run("count " + path("run.data") + " --cells optimal --frame 0").status, 2);
}

TEST_F(ParticleFiles, SameParticlesFromEveryFormat) {
  constexpr std::uint64_t kSeed = 11;
  const Packing p = sample_packing(300, kSeed);
  write_packing(path("p.h5"), p);
  const std::vector<std::pair<std::string, std::string>> files = {
      {"p.csv", as_csv(p)}, {"p.txt", as_text_with_diameters(p)}, {"data.lmp", lammps_data(p)},
      {"p.dump", as_dump(p, false)}};
  for (const auto& [name, text] : files) std::ofstream(path(name)) << text;
  const Packing ref = read_packing(path("p.h5"));
  for (const auto& [name, text] : files) {
    const Packing q = read_packing(path(name));
    EXPECT_EQ(q.radii, ref.radii) << name;
    EXPECT_EQ(q.positions, ref.positions) << name;
    EXPECT_EQ(q.box, ref.box) << name;
    EXPECT_EQ(q.packing_fraction(), ref.packing_fraction()) << name;
  }
}

struct Bad {
  const char* text;
  const char* field;
  const char* where;  // the "name:line" the message must name ("" : no line)
};

TEST_F(ParticleFiles, MalformedInputNamesFieldAndLine) {
  const Bad cases[] = {
      {"x,y,r\n1,2,0.5\n1,2,abc\n", "radius", "f:3"},
      {"x,y,r\n1,2,0.5\n1,2,-1\n", "radius", "f:3"},
      {"x,y,r\n1,2,0.5\n1,2\n", "row", "f:3"},
      {"x,y,r\n1,2,0.5,\n", "row", "f:2"},
      {"x y d\n1 nan 0.5\n", "y", "f:2"},
      {"a b c\n1 2 3\n", "header", "f:1"},
      {"x z r\n1 2 3\n", "header", "f:1"},
      {"1 2 3 4 5\n", "columns", "f:1"},
      {"# box 1 -2 3\nx y z r\n", "box", "f:1"},
      {"# boundary open\n1\n", "boundary", "f:1"},
      {"# box 1 1\nx y z r\n1 1 1 1\n", "box", ""},
      {"", "header", ""},
      {"x y r\n", "particles", ""},
      {"t\n\n2 atoms\n0 1 xlo xhi\n\nAtoms # atomic\n\n1 1 0 0 0\n", "atom_style", "f:6"},
      {"t\n\n2 atoms\n\nAtoms\n\n1 1 1 1 0 0 0\n2 1 1 1 0 0\n", "Atoms", "f:8"},
      {"t\n\n2 atoms\n\nAtoms\n\n1 1 1 1 0 0 0\n", "Atoms", ""},
      {"t\n\n2 atoms\n\nAtoms\n\n1 1 0 1 0 0 0\n2 1 1 1 0 0 0\n", "diameter", "f:7"},
      {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n0 inf 0 xy xz yz\n", "box", "f:7"},
      {"ITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS xy xz yz pp pp pp\n0 1 tilt\n0 1 0\n0 1 0\n", "BOX BOUNDS", "f:4"},
      {"t\n\n1 atoms\n", "Atoms", ""},
      {"ITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\nITEM: ATOMS x y z radius\n0 0 0 1\n", "ATOMS", ""},
      {"ITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\nITEM: ATOMS x y z q\n0 0 0 1\n", "ATOMS", "f:7"},
      {"ITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp\n0 1\n0 1\n", "BOX BOUNDS", "f:3"},
      {"ITEM: ATOMS x y z radius\n0 0 0 1\n", "ATOMS", "f:1"},
      {"ITEM: NUMBER OF ATOMS\n-1\n", "NUMBER OF ATOMS", "f:2"},
      // MercuryDPM .data: a snapshot with fewer particles than its header
      // declares, one cut short, a 2D header in a 3D file, an inverted domain.
      {"2 0 0 0 0 1 1 1\n0.5 0.5 0.5 0 0 0 0.1 0 0 0 0 0 0 0\n1 0 0 0 0 1 1 1\n", "particles", "f:3"},
      {"1 0 0 0 0 1 1 1 \n", "particles", "line 1"},
      {"0 0 0 0 0 1 1 1\n0 1 0 0 1 1\n", "header", "f:2"},
      {"1 0 0 0 2 1 1 1\n0.5 0.5 0.5 0 0 0 0.1 0 0 0 0 0 0 0\n", "header", "f:1"},
      {"1 0 0 0 1 1\n0.5 0.5 0 0 -1 0 0 0\n", "radius", "f:2"},
      {"bin\0ary", "file", ""},
  };
  for (const Bad& b : cases) {
    const std::string text(b.text, std::string_view(b.text).size() + (std::string_view(b.field) == "file" ? 3 : 0));
    try {
      to_packing(parse_particles(text, "f"), "f");
      ADD_FAILURE() << "accepted: " << b.text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), b.field) << b.text << " -> " << e.what();
      EXPECT_NE(std::string(e.what()).find(b.where), std::string::npos) << b.text << " -> " << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}

TEST_F(ParticleFiles, CliRefusesWithOneLineAndExit2) {
  std::ofstream(path("bad.txt")) << "x y r\n1 2 0.5\n1 2 zz\n";
  const Result r = hgrid_run("info " + path("bad.txt"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("bad.txt:3"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(r.out.empty());
}

/// Seeded byte mutations (replace, insert, delete, duplicate a line) of a
/// valid file of each format: every result is a particle set or an InputError.
TEST_F(ParticleFiles, MutatedFilesNeverCrashAReader) {
  constexpr std::uint64_t kSeed = 2026;
  constexpr int kMutantsPerFile = 1500;
  const Packing p = sample_packing(6, 7);
  Packing q;
  q.d = 2, q.box = {4, 5, 0}, q.positions = {1, 1, 3, 4}, q.radii = {0.5, 0.25};
  const std::string seeds[] = {as_csv(p), as_text_with_diameters(p), lammps_data(p), lammps_data(q),
                               as_dump(p, false), as_dump(p, true), "#format x_y_z_r\n1 2 3 0.5\n", "0.5\n1\n"};
  const std::string alphabet = "0123456789.,;-+eE#\n \tabcdefghijklmnopqrstuvwxyzITEM:ATOMS\r\0";
  std::mt19937_64 rng(kSeed);
  int accepted = 0, refused = 0;
  for (const std::string& seed : seeds)
    for (int m = 0; m < kMutantsPerFile; ++m) {
      std::string t = seed;
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits && !t.empty(); ++e) {
        const std::size_t at = rng() % t.size();
        const char c = alphabet[rng() % alphabet.size()];
        switch (rng() % 4) {
          case 0: t[at] = c; break;
          case 1: t.insert(t.begin() + static_cast<std::ptrdiff_t>(at), c); break;
          case 2: t.erase(at, 1 + rng() % 8); break;
          default: {
            const std::size_t end = t.find('\n', at);
            t.insert(at, t.substr(at, end == std::string::npos ? std::string::npos : end - at + 1));
          }
        }
      }
      try {
        ParticleSet s = parse_particles(t, "m");
        EXPECT_EQ(s.positions.size() % std::max(1, s.d), 0u);
        for (double r : s.radii) EXPECT_TRUE(std::isfinite(r) && r > 0);
        to_packing(std::move(s), "m");
        ++accepted;
      } catch (const InputError&) {
        ++refused;
      }
    }
  EXPECT_GT(accepted, 0);
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace hgrid::test
