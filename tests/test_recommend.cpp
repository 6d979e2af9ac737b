// hgrid recommend and the library behind it (advice/recommend,
// io/peer_settings): the same radii in every format and unit give the same
// sizes; nu and d from the file or the options; the K used is named; the
// LAMMPS lines run in LAMMPS and find every pair.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "bench/lammps_run.hpp"
#include "cli_support.hpp"
#include "hgridlab/advice/recommend.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/io/lammps_export.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/io/peer_settings.hpp"
#include "support.hpp"

namespace hgrid::test {
namespace {

/// The target: the same radii give the same sizes to this relative tolerance,
/// after unit conversion. Met exactly when the converted radii over r_min are
/// the same doubles (any format in one unit; diameters; a power-of-two unit).
constexpr double kSameSizesRelTol = 1e-12;
/// A decimal unit change (m -> mm) moves radii / r_min by an ulp; the optimum
/// of the smooth cost is fixed only to about sqrt(machine epsilon) of T, and
/// the sizes then agree to ~1e-10 (measured: 8.5e-11 at omega = 10).
constexpr double kDecimalUnitRelTol = 1e-9;
/// No calibration file, so that K is the paper's whatever the machine stores.
const std::string kNoCalibration = "HGRID_CALIBRATION=/nonexistent/calibration.json";

using Recommend = TempDir;

nlohmann::json recommend_json(const std::string& args) {
  const Result r = hgrid_run("recommend " + args + " --json", kNoCalibration);
  EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
  return r.status == 0 ? nlohmann::json::parse(r.out) : nlohmann::json();
}

void expect_same_sizes(const nlohmann::json& a, const nlohmann::json& b, double unit, const std::string& what,
                       double tol = kSameSizesRelTol) {
  ASSERT_EQ(a["sizes"].size(), b["sizes"].size()) << what;
  for (std::size_t h = 0; h < a["sizes"].size(); ++h) {
    const double sa = a["sizes"][h].get<double>() * unit, sb = b["sizes"][h].get<double>();
    EXPECT_NEAR(sa, sb, tol * sb) << what << " level " << h + 1;
  }
  EXPECT_NEAR(a["T_over_N"].get<double>(), b["T_over_N"].get<double>(), tol * b["T_over_N"].get<double>()) << what;
  ASSERT_EQ(a["lammps_collections"].size(), b["lammps_collections"].size()) << what;
  for (std::size_t h = 0; h < a["lammps_collections"].size(); ++h) {
    const double ca = a["lammps_collections"][h].get<double>() * unit, cb = b["lammps_collections"][h].get<double>();
    EXPECT_NEAR(ca, cb, tol * cb) << what << " LAMMPS collection " << h + 1;
  }
}

TEST_F(Recommend, SameRadiiInEveryFormatAndUnitGiveTheSameSizes) {
  constexpr std::uint64_t kSeed = 21;
  const Packing p = packing_from(random_scene<3>(2000, 0.3, -3, 20, Boundary::periodic, kSeed), Boundary::periodic);
  write_packing(path("p.h5"), p);
  std::string csv = "# box " + format_number(p.box[0]) + " " + format_number(p.box[1]) + " " + format_number(p.box[2]) +
                    "\nid,x,y,z,radius\n";
  std::string mm = "# box " + format_number(1000 * p.box[0]) + " " + format_number(1000 * p.box[1]) + " " +
                   format_number(1000 * p.box[2]) + "\nx y z diameter\n";
  std::string pow2 = "r\n";  // radii in a unit 1/1024 of the original: exact
  std::string radii, dump = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n" + std::to_string(p.size()) +
                            "\nITEM: BOX BOUNDS pp pp pp\n";
  for (int a = 0; a < 3; ++a) dump += "0 " + format_number(p.box[a]) + "\n";
  dump += "ITEM: ATOMS id type diameter x y z\n";
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double* x = &p.positions[3 * i];
    csv += std::to_string(i) + "," + format_number(x[0]) + "," + format_number(x[1]) + "," + format_number(x[2]) + "," +
           format_number(p.radii[i]) + "\n";
    mm += format_number(1000 * x[0]) + " " + format_number(1000 * x[1]) + " " + format_number(1000 * x[2]) + " " +
          format_number(2000 * p.radii[i]) + "\n";
    radii += format_number(p.radii[i]) + "\n";
    pow2 += format_number(1024 * p.radii[i]) + "\n";
    dump += std::to_string(i + 1) + " 1 " + format_number(2 * p.radii[i]) + " " + format_number(x[0]) + " " +
            format_number(x[1]) + " " + format_number(x[2]) + "\n";
  }
  std::ofstream(path("p.csv")) << csv;
  std::ofstream(path("mm.txt")) << mm;
  std::ofstream(path("radii.txt")) << radii;
  std::ofstream(path("pow2.txt")) << pow2;
  std::ofstream(path("p.dump")) << dump;
  std::ofstream(path("data.lmp")) << lammps_data(p);
  // The box's nu (--homogeneous): files with positions otherwise take the
  // density field, checked below and in tests/test_density_field.cpp.
  const nlohmann::json ref = recommend_json(path("p.h5") + " --homogeneous");
  ASSERT_FALSE(ref.is_null());
  EXPECT_GE(ref["levels"].get<int>(), 2);
  EXPECT_EQ(ref["nu_source"], "box");
  EXPECT_EQ(ref["K_source"], "paper");
  EXPECT_EQ(ref["K"].get<double>(), 0.2);
  const std::string nu = format_number(ref["nu"].get<double>());
  for (const std::string& f : {std::string("p.csv"), std::string("p.dump"), std::string("data.lmp")})
    expect_same_sizes(recommend_json(path(f) + " --homogeneous"), ref, 1.0, f);
  // The field: the same positions in every format give the same sizes.
  const nlohmann::json field = recommend_json(path("p.h5"));
  EXPECT_EQ(field["nu_source"], "field");
  for (const std::string& f : {std::string("p.csv"), std::string("p.dump"), std::string("data.lmp")})
    expect_same_sizes(recommend_json(path(f)), field, 1.0, f + " (field)", kDecimalUnitRelTol);
  expect_same_sizes(recommend_json(path("radii.txt") + " --d 3 --nu " + nu), ref, 1.0, "radii.txt");
  const nlohmann::json in_mm = recommend_json(path("mm.txt") + " --homogeneous");
  EXPECT_NEAR(in_mm["nu"].get<double>(), ref["nu"].get<double>(), kSameSizesRelTol);
  expect_same_sizes(recommend_json(path("pow2.txt") + " --d 3 --nu " + nu), ref, 1.0 / 1024, "pow2.txt");
  expect_same_sizes(recommend_json(path("mm.txt") + " --nu " + nu), ref, 1e-3, "mm.txt", kDecimalUnitRelTol);
}

TEST_F(Recommend, LibraryAgreesWithModelRadiiAndTheLinkedCell) {
  const auto s = random_scene<3>(3000, 0.4, -3, 10, Boundary::periodic, 3);
  double r_min = s.spheres[0].r;
  for (const auto& q : s.spheres) r_min = std::min(r_min, q.r);
  std::vector<double> radii;  // r_min = 1 exactly: `model --radii` works in the radii's unit, recommend in r_min's
  for (const auto& q : s.spheres) radii.push_back(q.r / r_min);
  const Recommendation r = recommend_cell_sizes(radii, ModelParams{3, 0.4, 0.2, Search::top_down});
  EXPECT_EQ(r.sizes.back(), 2 * r.r_max);
  for (std::size_t h = 1; h < r.sizes.size(); ++h) EXPECT_GT(r.sizes[h], r.sizes[h - 1]);
  EXPECT_EQ(r.linked_cell_size, 2 * r.r_max);
  EXPECT_GT(r.speedup(), 1.0);
  EXPECT_EQ(r.speedup(), r.linked_cell.T_over_N / r.model.T_over_N);
  // The same T/N as `hgrid model --radii` (which works in the radii's unit).
  std::string text;
  for (double v : radii) text += format_number(v) + "\n";
  std::ofstream(path("r.txt")) << text;
  const Result m = hgrid_run("model --radii " + path("r.txt") + " --nu 0.4 --d 3 --K 0.2 --json");
  ASSERT_EQ(m.status, 0) << m.err;
  const auto j = nlohmann::json::parse(m.out);
  EXPECT_EQ(j["levels"].get<int>(), r.levels());
  EXPECT_NEAR(j["T_over_N"].get<double>(), r.model.T_over_N, kSameSizesRelTol * r.model.T_over_N);
  EXPECT_THROW(recommend_cell_sizes({}, ModelParams{}), InputError);
  EXPECT_THROW(recommend_cell_sizes({1, -1}, ModelParams{}), InputError);
}

TEST_F(Recommend, NuAndDFromOptionsOrAClearError) {
  std::ofstream(path("r.txt")) << "0.5\n1\n2\n";
  Result r = hgrid_run("recommend " + path("r.txt") + " --d 3");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("nu: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--nu"), std::string::npos) << r.err;
  r = hgrid_run("recommend " + path("r.txt") + " --nu 0.5");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("d: "), std::string::npos) << r.err;
  EXPECT_EQ(hgrid_run("recommend " + path("r.txt") + " --nu 0 --d 3").status, 2);
  EXPECT_EQ(hgrid_run("recommend " + path("r.txt") + " --nu 0.5 --d 4").status, 2);
  const auto j = recommend_json(path("r.txt") + " --nu 0.5 --d 2 --K 0.8");
  EXPECT_EQ(j["K_source"], "given");
  EXPECT_EQ(j["K"].get<double>(), 0.8);
  EXPECT_EQ(j["d"].get<int>(), 2);
  EXPECT_TRUE(j["box"].is_null());
  const Result text = hgrid_run("recommend " + path("r.txt") + " --nu 0.5 --d 3", kNoCalibration);
  EXPECT_NE(text.out.find("K = 0.2 (the paper's value"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("neigh_modify collection/interval"), std::string::npos);
  EXPECT_NE(text.out.find("setHGridDistribution(USER);"), std::string::npos);
}

// What LAMMPS writes for a 2D run (write_data: every z = 0, zlo zhi = 0 1,
// and the zero tilts of a triclinic box): 2D, nu from the box's area; --d
// that disagrees with the file is refused.
TEST_F(Recommend, LammpsTwoDimensionalDataFileGivesNuFromItsArea) {
  std::ofstream f(path("2d.data"));
  f << "LAMMPS data file via write_data\n\n4 atoms\n1 atom types\n\n0 10 xlo xhi\n0 10 ylo yhi\n0 1 zlo zhi\n"
       "0 0 0 xy xz yz\n\nAtoms # sphere\n\n";
  const double x[4] = {1, 4, 6, 8}, d[4] = {2, 2, 1, 1};
  for (int i = 0; i < 4; ++i) f << i + 1 << " 1 " << d[i] << " 1 " << x[i] << " " << x[i] << " 0 0 0 0\n";
  f.close();
  const auto j = recommend_json(path("2d.data") + " --homogeneous");
  EXPECT_EQ(j["d"].get<int>(), 2);
  EXPECT_EQ(j["n"].get<int>(), 4);
  const double area = 2 * std::acos(-1.0) * (1 + 0.25);  // two discs of radius 1, two of 0.5
  EXPECT_NEAR(j["nu"].get<double>(), area / 100, 1e-12);
  EXPECT_EQ(recommend_json(path("2d.data") + " --d 2")["d"].get<int>(), 2);
  const Result r = hgrid_run("recommend " + path("2d.data") + " --d 3");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("d: "), std::string::npos) << r.err;
  EXPECT_EQ(hgrid_run("info " + path("2d.data") + " --d 3").status, 2);
  EXPECT_EQ(hgrid_run("info " + path("2d.data") + " --d 2").status, 0);
  for (const char* cmd : {"count", "pairs"}) {
    EXPECT_EQ(hgrid_run(std::string(cmd) + " " + path("2d.data") + " --cells optimal --d 3").status, 2) << cmd;
    EXPECT_EQ(hgrid_run(std::string(cmd) + " " + path("2d.data") + " --cells optimal --d 2").status, 0) << cmd;
  }
}

/// A calibration file that exists but does not read (an older format, say):
/// recommend falls back to the paper's K and says why; --K auto refuses it.
TEST_F(Recommend, UnreadableCalibrationFallsBackToThePapersKAndSaysWhy) {
  std::ofstream(path("r.txt")) << "0.5\n1\n2\n";
  std::ofstream(path("cal.json")) << "{\"format\": \"something else\"}\n";
  const std::string env = "HGRID_CALIBRATION=" + path("cal.json");
  Result r = hgrid_run("recommend " + path("r.txt") + " --nu 0.5 --d 3 --json", env);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["K_source"], "paper");
  EXPECT_EQ(j["K"].get<double>(), 0.2);
  EXPECT_NE(j["K_note"].get<std::string>().find("cal.json"), std::string::npos) << j["K_note"];
  EXPECT_EQ(hgrid_run("recommend " + path("r.txt") + " --nu 0.5 --d 3 --K auto", env).status, 2);
}

/// `hgrid model --radii` takes nu and d from the file (no silent 0.7) and
/// reads every format.
TEST_F(Recommend, ModelRadiiTakesNuAndDFromTheFile) {
  std::ofstream(path("p.csv")) << "# box 10 10\nx,y,r\n1,1,0.5\n5,5,1\n3,7,2\n";
  Result r = hgrid_run("model --radii " + path("p.csv") + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["params"]["d"], 2);
  EXPECT_EQ(j["params"]["nu_source"], "box");
  EXPECT_NEAR(j["params"]["nu"].get<double>(), M_PI * (0.25 + 1 + 4) / 100, 1e-15);
  r = hgrid_run("model --radii " + path("p.csv") + " --nu 0.3 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["params"]["nu"].get<double>(), 0.3);
  std::ofstream(path("r.txt")) << "0.5\n1\n2\n";
  r = hgrid_run("model --radii " + path("r.txt"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("nu: "), std::string::npos) << r.err;
  r = hgrid_run("model --radii " + path("r.txt") + " --nu 0.6 --json");  // the README's line: d defaults to 3
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["params"]["d"], 3);
}

TEST_F(Recommend, EveryJsonKeyIsDocumentedInHelp) {
  std::ofstream(path("r.csv")) << "# box 10 10\nx,y,r\n1,1,0.5\n5,5,1\n";
  const auto j = recommend_json(path("r.csv"));
  EXPECT_EQ(j["boundary"], "periodic (not in the file: assumed)");
  const std::string help = hgrid_run("recommend --help").out;
  for (const auto& [key, value] : j.items()) EXPECT_NE(help.find(" " + key), std::string::npos) << key;
}

TEST(PeerSettings, RoundedUpSizesAndLines) {
  EXPECT_EQ(rounded_up_sizes({1.0000001, 2.5, 7.123456789}), (std::vector<double>{1.00001, 2.5, 7.12346}));
  const std::vector<double> close = {1.0000001, 1.0000002};  // rounding would merge them: exact
  EXPECT_EQ(rounded_up_sizes(close), close);
  EXPECT_EQ(shortest_number(0.1), "0.1");
  const auto l = lammps_settings({4, 10, 40}, 0.5);
  EXPECT_EQ(l, (std::vector<std::string>{"neighbor 0.5 multi", "neigh_modify collection/interval 3 4 10 40",
                                         "comm_modify mode multi reduce/multi"}));
  const auto m = mercurydpm_settings({4, 10, 40}, Search::bottom_up);
  EXPECT_EQ(m[0], "setHGridMethod(BOTTOMUP);");
  EXPECT_EQ(m[2], "setHGridMaxLevels(3);");
  EXPECT_NE(m[5].find("{4, 10, 40}"), std::string::npos);
}

/// The pasted LAMMPS lines, in the exported script instead of its own, find
/// every overlapping pair (LAMMPS accepts the classes and the comm mode).
TEST(PeerSettings, RecommendedLammpsLinesFindEveryPair) {
  const auto lmp = find_lammps();
  if (!lmp) GTEST_SKIP() << "lmp not on PATH (apt-get install lammps)";
  const auto s = random_scene<3>(400, 0.4, -3, 6, Boundary::periodic, 9);
  const Packing p = packing_from(s, Boundary::periodic);
  Recommendation r = recommend_cell_sizes(p.radii, ModelParams{3, p.packing_fraction(), 0.2, Search::top_down});
  add_lammps_collections(r, p.radii, 3, p.packing_fraction());
  const fs::path dir = fs::temp_directory_path() / ("hgridlab_rec_" + std::to_string(::getpid()));
  LammpsScript sc;
  sc.builds = 2;
  export_lammps(dir.string(), p, sc);
  std::string in = lammps_input(p, sc), lines;
  ASSERT_GE(r.lammps_collections.size(), 1u);
  for (const auto& l : lammps_settings(r.lammps_collections, 0.0)) lines += l + "\n";
  const auto from = in.find("neighbor 0.0 multi"), to = in.find("neigh_modify every");
  ASSERT_NE(from, std::string::npos);
  in.replace(from, to - from, lines);
  std::ofstream(dir / "in.rec.lmp") << in;
  const LammpsResult res = run_lammps(*lmp, dir.string(), "in.rec.lmp");
  ASSERT_TRUE(res.ok) << res.error;
  EXPECT_EQ(res.pairs, (brute_pairs<3, Boundary::periodic>(s).size()));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace hgrid::test
