// Tilted (triclinic) boxes through files and the tool: the HDF5 attribute,
// the LAMMPS data file and dump, the exports, and the commands that search
// (pairs against its brute force, count) or refuse (walls, --decompose).
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <random>

#include "cli_support.hpp"
#include "hgridlab/advice/recommend.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/io/lammps_export.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/io/particle_file.hpp"
#include "hgridlab/measure/measurement.hpp"
#include "hgridlab/measure/pairs.hpp"
#include "support.hpp"

namespace hgrid::test {
namespace {

/// N spheres at uniform fractional coordinates of a tilted box (seeded).
Packing tilted_packing(int d, std::size_t n, const std::array<double, 3>& tilt, std::uint64_t seed,
                       const std::array<double, 3>& box = {30.0, 27.0, 24.0}) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Packing p;
  p.d = d;
  p.box = {box[0], box[1], d == 3 ? box[2] : 0.0};
  p.tilt = tilt;
  for (std::size_t i = 0; i < n; ++i) {
    p.radii.push_back(0.5 + 1.5 * u(rng));
    if (d == 3) {
      const std::array<double, 3> x = p.tilted_box<3>().cartesian({u(rng), u(rng), u(rng)});
      p.positions.insert(p.positions.end(), x.begin(), x.end());
    } else {
      const std::array<double, 2> x = p.tilted_box<2>().cartesian({u(rng), u(rng)});
      p.positions.insert(p.positions.end(), x.begin(), x.end());
    }
  }
  return p;
}

std::vector<Pair> pairs_of(const Packing& p, bool brute) {
  std::vector<Pair> out;
  const auto add = [&](int, std::uint32_t i, std::uint32_t j) { out.emplace_back(i, j); };
  if (brute) for_each_packing_pair_brute(p, add);
  else for_each_packing_pair(p, GridParams{{2.0, 4.0}}, add);
  std::sort(out.begin(), out.end());
  return out;
}

class TiltedFiles : public TempDir {};

TEST_F(TiltedFiles, Hdf5KeepsTheTiltsInAnyReader) {
  for (int d : {2, 3}) {
    const Packing p = tilted_packing(d, 400, {9.0, d == 3 ? -4.0 : 0.0, d == 3 ? 6.5 : 0.0}, 7 + d);
    const std::string f = path("t" + std::to_string(d) + ".h5");
    write_packing(f, p);
    for (Isolation iso : {Isolation::none, Isolation::child_process}) {
      const Packing q = read_packing(f, iso);
      EXPECT_EQ(q.tilt, p.tilt);
      EXPECT_EQ(pairs_of(q, false), pairs_of(p, true));
    }
  }
}

TEST_F(TiltedFiles, LammpsDataFileRoundTrip) {
  const Packing p = tilted_packing(3, 300, {-7.0, 5.0, 3.0}, 3);
  const std::string text = lammps_data(p);
  EXPECT_NE(text.find("-7 5 3 xy xz yz"), std::string::npos);
  const Packing q = to_packing(parse_particles(text, "t.data"), "t.data");
  EXPECT_EQ(q.tilt, p.tilt);
  EXPECT_EQ(pairs_of(q, false), pairs_of(p, true));
  // A 2D box leans only xy; xz or yz in a flat file is refused.
  Packing flat = tilted_packing(2, 50, {4.0, 0, 0}, 4);
  const Packing r = to_packing(parse_particles(lammps_data(flat), "f.data"), "f.data");
  EXPECT_EQ(r.d, 2);
  EXPECT_EQ(r.tilt[0], 4.0);
  std::string bad = lammps_data(flat);
  bad.replace(bad.find("4 0 0 xy xz yz"), 14, "4 1 0 xy xz yz");
  EXPECT_THROW(parse_particles(bad, "b.data"), InputError);
}

// A tilt beyond LAMMPS's limit: one line naming the field, the tilt and
// file:line; exit 2 and nothing written.
TEST_F(TiltedFiles, TiltBeyondTheLimitIsRefused) {
  const std::string data = "t\n\n1 atoms\n0 10 xlo xhi\n0 10 ylo yhi\n0 10 zlo zhi\n0 0 5.5 xy xz yz\n\n"
                           "Atoms # sphere\n\n1 1 1 1 1 1 1\n";
  try {
    parse_particles(data, "f.data");
    ADD_FAILURE() << "not refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "box");
    EXPECT_NE(std::string(e.what()).find("yz = 5.5"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("f.data:7"), std::string::npos) << e.what();
  }
  std::ofstream(path("f.data")) << data;
  const Result r = hgrid_run("export " + path("f.data") + " --lammps " + path("out"));
  EXPECT_EQ(r.status, 2);
  EXPECT_FALSE(fs::exists(path("out")));
  const std::string dump =
      "ITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS xy xz yz pp pp pp\n0 19 7\n0 10 0\n0 10 0\nITEM: ATOMS x y z radius\n1 1 1 1\n";
  EXPECT_THROW(parse_particles(dump, "f.dump"), InputError);  // xy = 7 > lx/2 = 6 (lx = 19 - 7)
}

// A triclinic dump's bounds enclose the tilted box; scaled columns are
// fractional coordinates. Hand-worked: lx = 10, ly = 8, lz = 6, xy = 2,
// xz = -1, yz = 3 from the origin (1, 2, 3): xlo_bound = 1 + min(0, 2, -1, 1)
// = 0, xhi_bound = 11 + max(0, 2, -1, 1) = 13, ylo_bound = 2, yhi_bound = 13.
TEST_F(TiltedFiles, LammpsDumpBoundsAndScaledColumns) {
  const std::string head =
      "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS xy xz yz pp pp pp\n0 13 2\n2 13 -1\n3 9 3\n";
  const ParticleSet s = parse_particles(head + "ITEM: ATOMS id xs ys zs radius\n1 0.5 0.25 0.5 1\n", "s.dump");
  ASSERT_TRUE(s.box);
  EXPECT_EQ(*s.box, (std::array<double, 3>{10, 8, 6}));
  EXPECT_EQ(s.tilt, (std::array<double, 3>{2, -1, 3}));
  // x = xlo + 0.5 * 10 + 0.25 * 2 + 0.5 * (-1) = 1 + 5, y = 2 + 2 + 1.5, z = 3 + 3; then minus the origin.
  ASSERT_EQ(s.positions.size(), 3u);
  EXPECT_DOUBLE_EQ(s.positions[0], 5.0);
  EXPECT_DOUBLE_EQ(s.positions[1], 3.5);
  EXPECT_DOUBLE_EQ(s.positions[2], 3.0);
  const ParticleSet x = parse_particles(head + "ITEM: ATOMS id x y z radius\n1 6 5.5 6 1\n", "x.dump");
  EXPECT_EQ(x.positions, s.positions);
  EXPECT_THROW(parse_particles(head + "ITEM: ATOMS id xs y zs radius\n1 0.5 5.5 0.5 1\n", "m.dump"), InputError);
}

TEST_F(TiltedFiles, ExtendedXyzLatticeHasTheTilts) {
  const Packing p = tilted_packing(3, 20, {2.0, -1.0, 3.0}, 5);
  write_packing(path("p.h5"), p);
  const Result r = hgrid_run("export " + path("p.h5") + " --xyz " + path("p.xyz"));
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(path("p.xyz"));
  std::string n, header;
  std::getline(in, n);
  std::getline(in, header);
  EXPECT_NE(header.find("Lattice=\"30 0 0 2 27 0 -1 3 24\""), std::string::npos) << header;
}

TEST_F(TiltedFiles, ToolSearchesAndRefuses) {
  const Packing p = tilted_packing(3, 800, {10.0, -6.0, 9.0}, 11);
  write_packing(path("p.h5"), p);
  const Result g = hgrid_run("pairs " + path("p.h5") + " --cells optimal --threads 2");
  const Result b = hgrid_run("pairs " + path("p.h5") + " --brute");
  ASSERT_EQ(g.status, 0) << g.err;
  ASSERT_EQ(b.status, 0) << b.err;
  const auto sorted_lines = [](const std::string& s) {
    std::vector<std::string> l;
    std::stringstream ss(s);
    for (std::string x; std::getline(ss, x);) l.push_back(x);
    std::sort(l.begin(), l.end());
    return l;
  };
  EXPECT_EQ(sorted_lines(g.out), sorted_lines(b.out));
  EXPECT_GT(sorted_lines(b.out).size(), 50u);
  const Result c = hgrid_run("count " + path("p.h5") + " --cells optimal --json");
  ASSERT_EQ(c.status, 0) << c.err;
  EXPECT_NE(c.out.find("\"tilt_inflation\""), std::string::npos);
  // c^d nu > 1 here: the mapped packing's random-centres model still answers.
  EXPECT_EQ(c.out.find("\"model_T_over_N\": null"), std::string::npos) << c.out.substr(0, 2000);
  EXPECT_NE(c.out.find("\"contacts\": " + std::to_string(sorted_lines(b.out).size())), std::string::npos);
  EXPECT_EQ(hgrid_run("count " + path("p.h5") + " --cells optimal --balance 2,8").status, 0);  // the mapped grid's pieces
  // The decomposed search cuts orthogonal bricks: refused, one line, exit 2.
  const Result dcmp = hgrid_run("count " + path("p.h5") + " --decompose --sizes 4");
  EXPECT_EQ(dcmp.status, 2);
  EXPECT_NE(dcmp.err.find("tilted box"), std::string::npos) << dcmp.err;
  // A tilted box with walls is no lattice.
  Packing w = p;
  w.boundary = Boundary::walls;
  EXPECT_THROW(validate(w), InputError);
}

// The model of a tilted box's work is the random-centres model of the mapped
// packing (docs/MODEL.md section 12): term by term on a seeded packing. A
// cubic box: the periodic grid fits its cells alike on every axis, as the
// model's one size per level assumes.
TEST(TiltedModel, CountsFollowTheMappedModel) {
  constexpr double kTol = 0.01;  // one packing of 3 * 10^4 random centres: counting noise ~0.3 %
  const Packing p = tilted_packing(3, 30000, {15.0, 0.0, 0.0}, 12, {30.0, 30.0, 30.0});
  Packing big = p;  // the same centres in a box 4x larger per side: nu ~ 0.1
  for (int a = 0; a < 3; ++a) big.box[a] *= 4;
  for (auto& t : big.tilt) t *= 4;
  for (auto& x : big.positions) x *= 4;
  MeasureOptions o;
  o.model = true;
  const Measurement m = measure(big, GridParams{{2.0, 4.0}}, o);
  ASSERT_GT(m.tilt_inflation, 1.0);
  ASSERT_TRUE(std::isfinite(m.model_T_over_N)) << m.model_skipped;
  EXPECT_NEAR(m.T_cd_over_N / m.model_T_cd_over_N, 1.0, kTol);
  EXPECT_NEAR(m.T_ca_over_N / m.model_T_ca_over_N, 1.0, kTol);
}

// `hgrid recommend` in a tilted box: the mapped packing's optimum, whose
// prediction is what the tilted grid counts with its sizes (random centres:
// within the counting noise), and whose sizes count no more than the
// untilted model's for the same particles.
TEST(TiltedModel, RecommendationIsTheMappedPackings) {
  constexpr double kTol = 0.02;  // 2 * 10^4 random centres
  Packing p = tilted_packing(3, 20000, {15.0, 0.0, 0.0}, 13, {30.0, 30.0, 30.0});
  for (int a = 0; a < 3; ++a) p.box[a] *= 3;
  for (auto& t : p.tilt) t *= 3;
  for (auto& x : p.positions) x *= 3;
  const double c = p.tilted_box<3>().inflation();
  ASSERT_GT(c, 1.2);
  const ModelParams mp{3, p.packing_fraction(), 0.2, Search::top_down};
  const Recommendation r = recommend_tilted(p.radii, mp, c);
  EXPECT_DOUBLE_EQ(r.tilt_inflation, c);
  const double got = measure(p, GridParams{r.sizes, Search::top_down}).T_over_N;
  EXPECT_NEAR(r.model.T_over_N, got, kTol * got);
  const double untilted = measure(p, GridParams{recommend_cell_sizes(p.radii, mp).sizes, Search::top_down}).T_over_N;
  EXPECT_LE(got, untilted * (1 + kTol));
  EXPECT_THROW(recommend_tilted(p.radii, mp, 0.5), InputError);
  EXPECT_EQ(recommend_tilted(p.radii, mp, 1.0).sizes, recommend_cell_sizes(p.radii, mp).sizes);
}

// A packing LAMMPS sheared (tests/data/beds/shear3d_o5.dump,
// experiments/shear/make_fixture.sh: nu = 0.55, omega = 5, xy at LAMMPS's
// limit lx / 2): `hgrid recommend`'s sizes (the mapped packing's) count
// within 5 % of the best of a scan of the untilted model's sizes and the
// linked cell, and its prediction is within 10 % of what they count.
TEST(TiltedModel, RecommendationOnAShearedPacking) {
  constexpr double kBestOfScanRelTol = 0.05, kPredictionRelTol = 0.10;
  const std::string file = std::string(HGRID_SOURCE_DIR) + "/tests/data/beds/shear3d_o5.dump";
  const ParticleSet s = read_particles(file);
  ASSERT_TRUE(s.tilted());
  const Packing p = to_packing(s, file);
  const auto count = [&](const std::vector<double>& sizes) {
    return measure(p, GridParams{sizes, Search::top_down}).T_over_N;
  };
  double best = count({2 * *std::max_element(p.radii.begin(), p.radii.end())});
  for (double nu : {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7})
    best = std::min(best, count(recommend_cell_sizes(p.radii, ModelParams{3, nu, 0.2}).sizes));
  const Recommendation r = recommend_tilted(p.radii, ModelParams{3, p.packing_fraction(), 0.2}, tilt_inflation(s));
  const double got = count(r.sizes);
  EXPECT_LE(got, (1 + kBestOfScanRelTol) * best);
  EXPECT_NEAR(r.model.T_over_N, got, kPredictionRelTol * got);
  // The tool gives the same sizes.
  const auto run = hgrid_run("recommend " + file + " --K 0.2 --json");
  ASSERT_EQ(run.status, 0) << run.err;
  const auto j = nlohmann::json::parse(run.out);
  EXPECT_NEAR(j["tilt_inflation"].get<double>(), tilt_inflation(s), 1e-12);
  EXPECT_EQ(j["sizes"].get<std::vector<double>>(), r.sizes);
}

}  // namespace
}  // namespace hgrid::test
