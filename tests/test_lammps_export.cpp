// LAMMPS export: data-file content, script options, bad input; and, when `lmp`
// is on PATH, LAMMPS's pair count (multi and bin) against brute force.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "hgridlab/measure/pairs.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/io/lammps_export.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "bench/lammps_run.hpp"
#include "support.hpp"

namespace hgrid::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string l; std::getline(ss, l);) out.push_back(l);
  return out;
}

template <int D, Boundary B>
std::uint64_t brute_count(const Scene<D>& s) {
  std::uint64_t c = 0;
  brute_force_pairs<D, B>(std::span<const Sphere<D>>(s.spheres), s.box, [&c](std::uint32_t, std::uint32_t) { ++c; });
  return c;
}

TEST(LammpsExport, DataFileHandWorked) {
  Packing p;
  p.d = 3;
  p.boundary = Boundary::periodic;
  p.box = {10, 20, 30};
  p.positions = {1, 2, 3, 4.5, 5, 6};
  p.radii = {0.5, 1.25};
  const auto l = lines(lammps_data(p));
  ASSERT_GE(l.size(), 13u);
  EXPECT_EQ(l[2], "2 atoms");
  EXPECT_EQ(l[3], "1 atom types");
  EXPECT_EQ(l[5], "0 10 xlo xhi");
  EXPECT_EQ(l[6], "0 20 ylo yhi");
  EXPECT_EQ(l[7], "0 30 zlo zhi");
  EXPECT_EQ(l[9], "Atoms # sphere");
  EXPECT_EQ(l[11], "1 1 1 1 1 2 3");        // id type diameter density x y z
  EXPECT_EQ(l[12], "2 1 2.5 1 4.5 5 6");
}

TEST(LammpsExport, TwoDimensionalAndWalls) {
  Packing p;
  p.d = 2;
  p.boundary = Boundary::walls;
  p.box = {8, 8, 0};
  p.positions = {0.1, 8};  // on the top wall: the box is widened a little
  p.radii = {0.1};
  const auto l = lines(lammps_data(p));
  EXPECT_EQ(l[7], "-0.5 0.5 zlo zhi");
  EXPECT_NE(l[6], "0 8 ylo yhi");
  EXPECT_EQ(l[11], "1 1 0.20000000000000001 1 0.10000000000000001 8 0");
  const std::string in = lammps_input(p, LammpsScript{LammpsNeighbor::bin, {}, 3});
  EXPECT_NE(in.find("dimension 2"), std::string::npos);
  EXPECT_NE(in.find("boundary f f p"), std::string::npos);
  EXPECT_NE(in.find("neighbor 0.0 bin"), std::string::npos);
  EXPECT_NE(in.find("run 3"), std::string::npos);
}

TEST(LammpsExport, CollectionsAndBadInput) {
  const auto s = random_scene<3>(50, 0.2, -3, 10, Boundary::periodic, 3);
  const Packing p = packing_from(s, Boundary::periodic);
  double rmax = 0;
  for (double r : p.radii) rmax = std::max(rmax, r);
  const auto c = geometric_collections(p, 3, 2.0);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_DOUBLE_EQ(c.front(), 2.0);
  EXPECT_DOUBLE_EQ(c.back(), 2 * rmax);
  const std::string in = lammps_input(p, LammpsScript{LammpsNeighbor::multi, c, 2});
  EXPECT_NE(in.find("neigh_modify collection/interval 3 2 "), std::string::npos);
  EXPECT_THROW(lammps_input(p, LammpsScript{LammpsNeighbor::multi, {2.0, rmax}, 2}), InputError);  // < 2 r_max
  EXPECT_THROW(lammps_input(p, LammpsScript{LammpsNeighbor::multi, {4.0, 3.0, 2 * rmax}, 2}), InputError);
  EXPECT_THROW(geometric_collections(p, 0, 2.0), InputError);
  Packing empty;
  EXPECT_THROW(lammps_data(empty), InputError);
}

TEST(LammpsExport, LogParsing) {
  const std::string log =
      "Loop time of 0.5 on 1 procs for 4 steps with 10 atoms\n\nMPI task timing breakdown:\n"
      "Section |  min time  |  avg time  |  max time  |%varavg| %total\n"
      "---------------------------------------------------------------\n"
      "Pair    | 0.01       | 0.01       | 0.01       |   0.0 |  2.00\n"
      "Neigh   | 0.4        | 0.4        | 0.4        |   0.0 | 80.00\n"
      "Comm    | 0.05       | 0.05       | 0.05       |   0.0 | 10.00\n"
      "Total # of neighbors = 1234\nNeighbor list builds = 4\n";
  const LammpsResult r = parse_lammps_log(log);
  EXPECT_TRUE(r.ok);
  EXPECT_DOUBLE_EQ(r.neigh_seconds, 0.4);
  EXPECT_DOUBLE_EQ(r.comm_seconds, 0.05);
  EXPECT_EQ(r.pairs, 1234u);
  EXPECT_EQ(r.builds, 4u);
  EXPECT_DOUBLE_EQ(r.seconds_per_build(), 0.1);
  EXPECT_FALSE(parse_lammps_log("ERROR: Too many neighbor bins (src/nbin_multi.cpp:99)\n").ok);
}

template <int D, Boundary B>
void check_with_lammps(double nu, std::uint64_t seed) {
  const auto lmp = find_lammps();
  if (!lmp) GTEST_SKIP() << "lmp not on PATH (apt-get install lammps)";
  const auto s = random_scene<D>(300, nu, -3, 4, B, seed);
  const Packing p = packing_from(s, B);
  const fs::path dir = fs::temp_directory_path() / ("hgridlab_lmp_" + std::to_string(::getpid()) + "_" +
                                                    std::to_string(D) + to_string(B));
  LammpsScript sc;
  sc.builds = 2;
  sc.collections = geometric_collections(p, 3, 2.0);
  export_lammps(dir.string(), p, sc);
  const std::uint64_t expected = brute_count<D, B>(s);
  ASSERT_GT(expected, 0u);
  for (const char* script : {"in.multi.lmp", "in.bin.lmp"}) {
    const LammpsResult r = run_lammps(*lmp, dir.string(), script);
    ASSERT_TRUE(r.ok) << script << ": " << r.error;
    EXPECT_EQ(r.pairs, expected) << script;
    EXPECT_EQ(r.builds, 2u) << script;
  }
  fs::remove_all(dir);
}

/// What LAMMPS itself writes, read back: after the timed builds the script
/// turns the box triclinic (tilts 0, as a shear run starts) and writes a data
/// file and dumps with x y z, scaled xs ys zs and unwrapped xu yu zu, radius
/// and diameter columns (2D: z = 0 in a box around it). Each reads as a D-
/// dimensional packing of the same radii and centres, and its pairs are those
/// LAMMPS's own list counted as touching.
template <int D>
void read_what_lammps_writes(std::uint64_t seed) {
  const auto lmp = find_lammps();
  if (!lmp) GTEST_SKIP() << "lmp not on PATH (apt-get install lammps)";
  constexpr double kPositionTol = 1e-9;  // relative to the box: LAMMPS prints 16 digits, scaled columns round
  const auto sc0 = random_scene<D>(300, 0.4, -3, 4, Boundary::periodic, seed);
  const Packing p = packing_from(sc0, Boundary::periodic);
  const fs::path dir = fs::temp_directory_path() / ("hgridlab_lmpw_" + std::to_string(::getpid()) + "_" + std::to_string(D));
  LammpsScript sc;
  sc.builds = 1;
  export_lammps(dir.string(), p, sc);
  std::ifstream bin(dir / "in.bin.lmp");
  std::stringstream script;
  script << bin.rdbuf()
         << "change_box all triclinic\nwrite_data written.data\n"
            "write_dump all custom x.dump id x y z radius modify sort id format float %.17g\n"
            "write_dump all custom s.dump id xs ys zs diameter modify sort id format float %.17g\n"
            "write_dump all custom u.dump id xu yu zu radius modify sort id format float %.17g\n";
  std::ofstream(dir / "in.write.lmp") << script.str();
  const LammpsResult r = run_lammps(*lmp, dir.string(), "in.write.lmp");
  ASSERT_TRUE(r.ok) << r.error;
  const std::uint64_t expected = brute_count<D, Boundary::periodic>(sc0);
  EXPECT_EQ(r.pairs, expected);
  for (const char* f : {"written.data", "x.dump", "s.dump", "u.dump"}) {
    SCOPED_TRACE(std::string(f) + " seed " + std::to_string(seed));
    const Packing q = read_packing((dir / f).string());
    ASSERT_EQ(q.d, D);
    ASSERT_EQ(q.size(), p.size());
    for (int a = 0; a < D; ++a) EXPECT_NEAR(q.box[a], p.box[a], kPositionTol * p.box[a]);
    std::vector<double> rp = p.radii, rq = q.radii;
    std::sort(rp.begin(), rp.end());
    std::sort(rq.begin(), rq.end());
    for (std::size_t i = 0; i < rp.size(); ++i) EXPECT_NEAR(rq[i], rp[i], 1e-12 * rp[i]);
    if (std::string(f) != "written.data") {  // dumps sorted by id: the same order
      for (std::size_t i = 0; i < p.positions.size(); ++i) {
        const double A = p.box[i % D];
        double dx = std::fmod(q.positions[i] - p.positions[i], A);
        dx = std::min(std::abs(dx), A - std::abs(dx));
        EXPECT_LT(dx, kPositionTol * A) << "coordinate " << i;
      }
    }
    Scene<D> back;
    for (int a = 0; a < D; ++a) back.box[a] = q.box[a];
    for (std::size_t i = 0; i < q.size(); ++i) {
      Sphere<D> sp;
      for (int a = 0; a < D; ++a) sp.x[a] = q.positions[i * D + a];
      sp.r = q.radii[i];
      back.spheres.push_back(sp);
    }
    EXPECT_EQ((brute_count<D, Boundary::periodic>(back)), r.pairs);
  }
  fs::remove_all(dir);
}

/// A sheared box, as LAMMPS writes it: the packing read into LAMMPS, its box
/// made triclinic and sheared by `fix deform` (xy, and in 3D xz and yz, to
/// a third of the edge they lean along; the atoms remapped with the box),
/// then a data file and dumps with x y z, scaled xs ys zs (fractional in a
/// tilted box) and unwrapped xu yu zu. Each reads as the tilted packing:
/// the tilts LAMMPS ended with, and the pairs LAMMPS's own list counted in
/// the sheared box, found by the tilted grid and by its brute force alike.
/// narrow: a few spheres in a box sheared to LAMMPS's limit, narrower than
/// four largest radii (where the lattice's rounding alone can miss the
/// nearest image; LAMMPS's own examples sheared by fix deform get there).
/// LAMMPS's list counts each image's contact; in these scenes no pair
/// touches through two images, so its count is the pairs'.
template <int D>
void read_what_a_sheared_run_writes(std::uint64_t seed, bool narrow = false) {
  const auto lmp = find_lammps();
  if (!lmp) GTEST_SKIP() << "lmp not on PATH (apt-get install lammps)";
  const auto sc0 = random_scene<D>(narrow ? (D == 2 ? 6 : 16) : 300, 0.4, -3, 4, Boundary::periodic, seed);
  const Packing p = packing_from(sc0, Boundary::periodic);
  const fs::path dir = fs::temp_directory_path() / ("hgridlab_lmps_" + std::to_string(::getpid()) + "_" + std::to_string(D));
  LammpsScript sc;
  sc.builds = 1;
  export_lammps(dir.string(), p, sc);
  const double f = narrow ? 0.5 : 1.0 / 3;
  const std::array<double, 3> tilt{f * p.box[0], D == 3 ? -f * p.box[0] : 0.0, D == 3 ? f * p.box[1] : 0.0};
  std::ifstream bin(dir / "in.bin.lmp");
  std::stringstream script;
  script.precision(17);
  script << bin.rdbuf() << "change_box all triclinic\ntimestep 0.001\nfix shear all deform 1 xy final " << tilt[0];
  if (D == 3) script << " xz final " << tilt[1] << " yz final " << tilt[2];
  script << " remap x\nrun 20\nunfix shear\nrun 0\nwrite_data sheared.data\n"
            "write_dump all custom x.dump id x y z radius modify sort id format float %.17g\n"
            "write_dump all custom s.dump id xs ys zs diameter modify sort id format float %.17g\n"
            "write_dump all custom u.dump id xu yu zu radius modify sort id format float %.17g\n";
  std::ofstream(dir / "in.shear.lmp") << script.str();
  const LammpsResult r = run_lammps(*lmp, dir.string(), "in.shear.lmp");
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_GT(r.pairs, 0u);
  for (const char* f : {"sheared.data", "x.dump", "s.dump", "u.dump"}) {
    SCOPED_TRACE(std::string(f) + " seed " + std::to_string(seed));
    const Packing q = read_packing((dir / f).string());
    ASSERT_EQ(q.d, D);
    ASSERT_EQ(q.size(), p.size());
    ASSERT_TRUE(q.tilted());
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(q.tilt[k], tilt[k], 1e-9 * p.box[0]) << "tilt " << k;
    if (narrow) {
      const double w = D == 2 ? q.tilted_box<2>().min_width() : q.tilted_box<3>().min_width();
      const double rmax = *std::max_element(q.radii.begin(), q.radii.end());
      EXPECT_LT(w, 4 * rmax) << "the box must be narrower than the rounding alone serves";
    }
    for (int a = 0; a < D; ++a) EXPECT_NEAR(q.box[a], p.box[a], 1e-9 * p.box[a]);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> grid, brute;
    const auto [rmin, rmax] = std::minmax_element(q.radii.begin(), q.radii.end());
    for_each_packing_pair(q, GridParams{exponential_sizes(2, *rmin, *rmax)},
                          [&](int, std::uint32_t i, std::uint32_t j) { grid.emplace_back(i, j); });
    for_each_packing_pair_brute(q, [&](int, std::uint32_t i, std::uint32_t j) { brute.emplace_back(i, j); });
    std::sort(grid.begin(), grid.end());
    std::sort(brute.begin(), brute.end());
    EXPECT_EQ(grid, brute);
    EXPECT_EQ(grid.size(), r.pairs);
    if (std::string(f) == "sheared.data") {  // exported again: LAMMPS reads our tilted box and finds the same pairs
      const fs::path again = dir / "again";
      LammpsScript sc2;
      sc2.builds = 1;
      sc2.collections = geometric_collections(q, 3, 2.0);
      export_lammps(again.string(), q, sc2);
      for (const char* script : {"in.multi.lmp", "in.bin.lmp"}) {
        const LammpsResult r2 = run_lammps(*lmp, again.string(), script);
        ASSERT_TRUE(r2.ok) << script << ": " << r2.error;
        EXPECT_EQ(r2.pairs, grid.size()) << script;
      }
    }
  }
  fs::remove_all(dir);
}

TEST(LammpsRun, ShearedBoxLammpsWritesIsRead3D) { read_what_a_sheared_run_writes<3>(23); }
TEST(LammpsRun, ShearedBoxLammpsWritesIsRead2D) { read_what_a_sheared_run_writes<2>(24); }
TEST(LammpsRun, NarrowShearedBoxLammpsWritesIsRead3D) { read_what_a_sheared_run_writes<3>(25, true); }
TEST(LammpsRun, NarrowShearedBoxLammpsWritesIsRead2D) { read_what_a_sheared_run_writes<2>(26, true); }

TEST(LammpsRun, FilesLammpsWritesAreRead3D) { read_what_lammps_writes<3>(21); }
TEST(LammpsRun, FilesLammpsWritesAreRead2D) { read_what_lammps_writes<2>(22); }

TEST(LammpsRun, PeriodicPairsEqualBruteForce3D) { check_with_lammps<3, Boundary::periodic>(0.4, 5); }
TEST(LammpsRun, WallPairsEqualBruteForce3D) { check_with_lammps<3, Boundary::walls>(0.4, 6); }
TEST(LammpsRun, PeriodicPairsEqualBruteForce2D) { check_with_lammps<2, Boundary::periodic>(0.5, 7); }

}  // namespace
}  // namespace hgrid::test

namespace hgrid::test {
namespace {

int hgrid_status(const std::string& args) {
  const int st = std::system((std::string(HGRID_BINARY) + " " + args + " >/dev/null 2>&1").c_str());
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

TEST(LammpsCli, ExportWritesFilesAndRejectsBadInput) {
  const fs::path dir = fs::temp_directory_path() / ("hgridlab_export_" + std::to_string(::getpid()));
  const std::string csv = (dir / "p.csv").string();
  fs::create_directories(dir);
  std::ofstream(csv) << "# box 10 10 10\n# boundary periodic\nx,y,z,r\n1,1,1,0.5\n2,1,1,0.75\n5,5,5,1\n";
  EXPECT_EQ(hgrid_status("export " + csv + " --lammps " + (dir / "out").string()), 0);
  EXPECT_TRUE(fs::exists(dir / "out" / "data.lmp"));
  EXPECT_TRUE(fs::exists(dir / "out" / "in.multi.lmp"));
  EXPECT_TRUE(fs::exists(dir / "out" / "in.bin.lmp"));
  EXPECT_EQ(hgrid_status("export --lammps " + (dir / "x").string()), 2);                           // no packing
  EXPECT_EQ(hgrid_status("export " + csv + " --lammps " + (dir / "y").string() + " --collections 1,1.5"), 2);  // < d_max = 2
  EXPECT_FALSE(fs::exists(dir / "y"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace hgrid::test
