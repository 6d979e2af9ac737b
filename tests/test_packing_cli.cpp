// Packing files (HDF5, CSV) and the `hgrid pairs` / `hgrid count` commands end to end.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "hgridlab/base/error.hpp"
#include "hgridlab/packing/packing.hpp"
#include "hgridlab/packing/packing_sizes.hpp"
#include "cli_support.hpp"
#include "hgridlab/base/threads.hpp"
#include "support.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/io/provenance.hpp"

namespace hgrid::test {
namespace {

using PackingFiles = TempDir;

TEST_F(PackingFiles, Hdf5RoundTrip) {
  auto p = packing_from(random_scene<3>(500, 0.3, -3, 10, Boundary::walls, 5), Boundary::walls);
  p.num_attrs["seed"] = 5;
  p.str_attrs["placement"] = "random";
  write_packing(path("a.h5"), p);
  const Packing q = read_packing(path("a.h5"));
  EXPECT_EQ(q.d, 3);
  EXPECT_EQ(q.boundary, Boundary::walls);
  EXPECT_EQ(q.positions, p.positions);  // bit for bit
  EXPECT_EQ(q.radii, p.radii);
  EXPECT_EQ(q.num_attrs.at("seed"), 5);
  EXPECT_EQ(q.str_attrs.at("placement"), "random");
  EXPECT_EQ(q.str_attrs.at("git_hash"), git_hash());
  for (const auto& e : fs::directory_iterator(dir_)) EXPECT_EQ(e.path().filename(), "a.h5");  // no temp left
}

TEST_F(PackingFiles, TruncatedHdf5IsRejected) {
  auto p = packing_from(random_scene<3>(2000, 0.3, -3, 10, Boundary::walls, 6), Boundary::walls);
  write_packing(path("a.h5"), p);
  fs::resize_file(path("a.h5"), fs::file_size(path("a.h5")) / 2);
  EXPECT_THROW(read_packing(path("a.h5")), InputError);
  std::ofstream(path("junk.h5")) << "not hdf5";
  EXPECT_THROW(read_packing(path("junk.h5")), InputError);
  EXPECT_THROW(read_packing(path("missing.h5")), InputError);
}

TEST_F(PackingFiles, Csv) {
  std::ofstream(path("p.csv")) << "# my particles\n# box 10 12\n# boundary periodic\nx,y,r\n1,2,0.5\n-1,13,0.25\n";
  const Packing p = read_packing(path("p.csv"));
  EXPECT_EQ(p.d, 2);
  EXPECT_EQ(p.boundary, Boundary::periodic);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_DOUBLE_EQ(p.positions[2], 9.0);  // wrapped into [0, A)
  EXPECT_DOUBLE_EQ(p.positions[3], 1.0);
  std::ofstream(path("nobox.csv")) << "x,y,r\n1,2,0.5\n";
  EXPECT_THROW(read_packing(path("nobox.csv")), InputError);
  std::ofstream(path("bad.csv")) << "# box 10 10\n# boundary walls\nx,y,r\n1,2,abc\n";
  EXPECT_THROW(read_packing(path("bad.csv")), InputError);
  std::ofstream(path("out.csv")) << "# box 10 10\n# boundary walls\nx,y,r\n11,2,1\n";
  EXPECT_THROW(read_packing(path("out.csv")), InputError);
  std::ofstream(path("neg.csv")) << "# box 10 10\n# boundary walls\nx,y,r\n1,2,-1\n";
  EXPECT_THROW(read_packing(path("neg.csv")), InputError);
  std::ofstream(path("nan.csv")) << "# box 10 10\n# boundary walls\nx,y,r\nnan,2,1\n";
  EXPECT_THROW(read_packing(path("nan.csv")), InputError);
}

using Cli = TempDir;

/// The lines of a command's output, sorted (pairs come in any order).
std::vector<std::string> sorted_lines(const std::string& t) {
  std::vector<std::string> v;
  std::istringstream ss(t);
  for (std::string l; std::getline(ss, l);) v.push_back(l);
  std::sort(v.begin(), v.end());
  return v;
}

TEST_F(Cli, PairsEqualBruteForce) {
  const auto s = random_scene<3>(3000, 0.5, -3, 30, Boundary::periodic, 11);
  write_packing(path("p.h5"), packing_from(s, Boundary::periodic));
  const Result grid = hgrid_run("pairs " + path("p.h5") + " --sizes 3,10,60.001 --search bottomup");
  const Result brute = hgrid_run("pairs " + path("p.h5") + " --brute");
  ASSERT_EQ(grid.status, 0) << grid.err;
  ASSERT_EQ(brute.status, 0) << brute.err;
  EXPECT_GT(sorted_lines(brute.out).size(), 100u);
  EXPECT_EQ(sorted_lines(grid.out), sorted_lines(brute.out));
}

// --threads: the same pair set (in another order) and the same counts for
// 1, 2, 3 and 8 threads; bad values get one line and status 2.
TEST_F(Cli, ThreadsGiveTheSameResults) {
  const auto s = random_scene<3>(12000, 0.5, -3, 20, Boundary::periodic, 12);
  write_packing(path("p.h5"), packing_from(s, Boundary::periodic));
  const Result brute = hgrid_run("pairs " + path("p.h5") + " --brute");
  ASSERT_EQ(brute.status, 0) << brute.err;
  nlohmann::json one;
  for (const int t : {1, 2, 3, 8}) {
    SCOPED_TRACE("threads = " + std::to_string(t));
    const Result p = hgrid_run("pairs " + path("p.h5") + " --sizes 2.5,8,40.001 --threads " + std::to_string(t));
    ASSERT_EQ(p.status, 0) << p.err;
    EXPECT_EQ(sorted_lines(p.out), sorted_lines(brute.out));
    const Result c = hgrid_run("count " + path("p.h5") + " --cells optimal --json --threads " + std::to_string(t));
    ASSERT_EQ(c.status, 0) << c.err;
    auto j = nlohmann::json::parse(c.out);
    EXPECT_EQ(j["threads"], t);
    for (const char* k : {"threads", "seconds_build", "seconds_query"}) j.erase(k);
    if (t == 1) one = j;
    EXPECT_EQ(j, one);
  }
  // The default (0, all cores) follows OMP_NUM_THREADS.
  const Result env = hgrid_run("count " + path("p.h5") + " --sizes 40.001 --json", "OMP_NUM_THREADS=3");
  ASSERT_EQ(env.status, 0) << env.err;
  if (kHaveThreads) {
    EXPECT_EQ(nlohmann::json::parse(env.out)["threads"], 3);
  }
  for (const char* bad : {"-1", "1025", "two"}) {
    const Result r = hgrid_run("count " + path("p.h5") + " --sizes 40.001 --threads " + bad);
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_NE(r.err.find("threads"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty());
  }
}

// A file without '# boundary' is periodic, and count and info say it was assumed.
TEST_F(Cli, AssumedBoundaryIsStated) {
  std::ofstream(path("nb.csv")) << "# box 4 4\nx,y,r\n0.5,0.5,0.5\n1.4,0.5,0.5\n";
  std::ofstream(path("wb.csv")) << "# box 4 4\n# boundary walls\nx,y,r\n0.5,0.5,0.5\n1.4,0.5,0.5\n";
  const Result a = hgrid_run("count " + path("nb.csv") + " --sizes 2 --json");
  ASSERT_EQ(a.status, 0) << a.err;
  EXPECT_EQ(nlohmann::json::parse(a.out)["boundary_source"], "assumed: not in the file");
  const Result w = hgrid_run("count " + path("wb.csv") + " --sizes 2 --json");
  ASSERT_EQ(w.status, 0) << w.err;
  EXPECT_EQ(nlohmann::json::parse(w.out)["boundary_source"], "file");
  const Result t = hgrid_run("count " + path("nb.csv") + " --sizes 2");
  EXPECT_NE(t.out.find("periodic (not in the file: assumed)"), std::string::npos) << t.out;
  const Result i = hgrid_run("info " + path("nb.csv"));
  EXPECT_NE(i.out.find("periodic (not in the file: assumed)"), std::string::npos) << i.out;
}

TEST(PackingSizes, LevelsFittedToTheSameCellsAreMerged) {
  Packing p;
  p.d = 2;
  p.box = {100.0, 100.0, 0.0};
  // 100 / 19.9 and 100 / 19.95 both give 5 cells per axis: one level.
  EXPECT_EQ(merge_fitted_levels({3.0, 19.9, 19.95}, p), (std::vector<double>{3.0, 19.95}));
  EXPECT_EQ(merge_fitted_levels({3.0, 16.0, 19.95}, p), (std::vector<double>{3.0, 16.0, 19.95}));  // 6 and 5 cells
  p.boundary = Boundary::walls;  // cells not fitted: unchanged
  EXPECT_EQ(merge_fitted_levels({3.0, 19.9, 19.95}, p), (std::vector<double>{3.0, 19.9, 19.95}));
}

TEST_F(Cli, ReportedSizesCanBeGivenBack) {
  // The sizes `count --cells optimal` reports (the grid's) are a valid --sizes
  // list with the same counts. This 2D packing's optimum had two top levels
  // fitted to the same cells (reported twice, refused by --sizes).
  const Result g = hgrid_run("generate --d 2 --n 100000 --nu 0.4 --alpha -3 --omega 10 --placement excluded --seed 1 --quiet --out " +
                             path("p.h5"));
  ASSERT_EQ(g.status, 0) << g.err;
  const Result a = hgrid_run("count " + path("p.h5") + " --cells optimal --json");
  ASSERT_EQ(a.status, 0) << a.err;
  const auto ja = nlohmann::json::parse(a.out);
  std::string sizes;
  for (const auto& s : ja["sizes"]) sizes += (sizes.empty() ? "" : ",") + format_number(s.get<double>());
  const Result b = hgrid_run("count " + path("p.h5") + " --sizes " + sizes + " --json");
  ASSERT_EQ(b.status, 0) << b.err << sizes;
  const auto jb = nlohmann::json::parse(b.out);
  EXPECT_EQ(jb["narrow_phase_checks"], ja["narrow_phase_checks"]);
  EXPECT_EQ(jb["cell_accesses"], ja["cell_accesses"]);
}

TEST_F(Cli, CountJson) {
  std::ofstream(path("p.csv")) << "# box 4 4\n# boundary walls\nx,y,r\n0.5,0.5,0.5\n1.4,0.5,0.5\n2.5,0.5,0.5\n2.5,2.5,0.5\n";
  const Result r = hgrid_run("count " + path("p.csv") + " --sizes 2 --json --K 0.5");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["n"], 4);
  EXPECT_EQ(j["cell_accesses"], 11);  // as worked out in test_hgrid_cases.cpp
  EXPECT_EQ(j["narrow_phase_checks"], 6);
  EXPECT_EQ(j["contacts"], 1);
  EXPECT_DOUBLE_EQ(j["T_over_N"].get<double>(), (6 + 0.5 * 11) / 4.0);
  EXPECT_EQ(j["sizes"].size(), 1u);
  EXPECT_EQ(j["particles_per_level"][0], 4);
}

// docs/MEASUREMENT.md's table of fields is the tool's own.
TEST_F(Cli, MeasurementFieldsAreDocumented) {
  const Result r = hgrid_run("fields --markdown");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream f(std::string(HGRID_SOURCE_DIR) + "/docs/MEASUREMENT.md");
  const std::string doc((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(r.out.empty());
  EXPECT_NE(doc.find(r.out), std::string::npos) << "regenerate the table with `hgrid fields --markdown`";
}

TEST_F(Cli, CountReportsTheWallPairsModelAsked) {
  // A walled excluded-volume packing: the same counts, two wall closures of
  // the excluded-volume model; the product charges the wall layers the bulk
  // pair excess, so it predicts more checks (docs/MODEL.md section 8).
  const Result g = hgrid_run("generate --n 400 --nu 0.5 --alpha -3 --omega 5 --boundary walls --placement excluded "
                             "--seed 3 --out " + path("w.h5"));
  ASSERT_EQ(g.status, 0) << g.err;
  const auto count = [&](const std::string& extra) {
    const Result r = hgrid_run("count " + path("w.h5") + " --cells optimal --threads 1 --json" + extra);
    EXPECT_EQ(r.status, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const auto layer = count(""), product = count(" --wall-pairs product");
  EXPECT_EQ(layer["wall_pairs"], "layer");
  EXPECT_EQ(product["wall_pairs"], "product");
  EXPECT_EQ(layer["narrow_phase_checks"], product["narrow_phase_checks"]);
  EXPECT_LT(layer["model_excluded_T_cd_over_N"].get<double>(), product["model_excluded_T_cd_over_N"].get<double>());
  EXPECT_EQ(count(" --wall-pairs layer")["model_excluded_T_over_N"], layer["model_excluded_T_over_N"]);
  // --model: fewer predictions, the same counts and the same paper's model.
  const auto paper = count(" --model paper"), none = count(" --model none");
  for (const auto* j : {&paper, &none}) EXPECT_EQ((*j)["narrow_phase_checks"], layer["narrow_phase_checks"]);
  EXPECT_EQ(paper["model_T_over_N"], layer["model_T_over_N"]);
  EXPECT_TRUE(paper["model_excluded_T_over_N"].is_null());
  EXPECT_TRUE(none["model_T_over_N"].is_null());
  EXPECT_TRUE(none["model_excluded_T_over_N"].is_null());
}

TEST_F(Cli, BadInputExitsWithStatus2) {
  std::ofstream(path("p.csv")) << "# box 4 4\n# boundary walls\nx,y,r\n0.5,0.5,0.5\n";
  std::ofstream(path("neg.csv")) << "# box 4 4\n# boundary walls\nx,y,r\n0.5,0.5,-0.5\n";
  const std::pair<std::string, std::string> cases[] = {
      {"count " + path("p.csv") + " --sizes 2,1", "sizes"},
      {"count " + path("p.csv") + " --sizes 0.5", "sizes"},
      {"count " + path("p.csv") + " --sizes 2,abc", "sizes"},
      {"count " + path("p.csv") + " --sizes 2 --search sideways", "search"},
      {"count " + path("p.csv") + " --sizes 2 --wall-pairs kirkwood", "wall-pairs"},
      {"count " + path("p.csv") + " --sizes 2 --model everything", "model"},
      {"count " + path("neg.csv") + " --sizes 2", "radius"},
      {"count " + path("nothere.h5") + " --sizes 2", "file"},
      {"count " + path("p.csv"), "sizes"},
      {"pairs " + path("p.csv") + " --sizes 2 --bogus", "bogus"},
  };
  for (const auto& [args, word] : cases) {
    const Result r = hgrid_run(args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_NE(r.err.find(word), std::string::npos) << args << " -> " << r.err;
    EXPECT_TRUE(r.out.empty()) << args;
  }
  EXPECT_EQ(hgrid_run("count --help").status, 0);
  EXPECT_EQ(hgrid_run("pairs --help").status, 0);
}

TEST_F(Cli, OutputThatCannotBeWrittenLeavesNothingBehind) {
  // The output path is a directory: the rename fails; exit 2 naming the
  // output, and no temporary file is left beside it.
  fs::create_directories(path("out.h5"));
  const Result r =
      hgrid_run("generate --d 2 --n 50 --nu 0.1 --alpha -3 --omega 4 --seed 3 --out " + path("out.h5"));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("out"), std::string::npos) << r.err;
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
}

TEST_F(Cli, VersionNamesTheCommit) {
  const Result r = hgrid_run("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind(std::string("hgrid ") + version() + " (" + git_hash(), 0), 0u) << r.out;
}

TEST_F(Cli, DpmSceneWritesHdf5AndCsvLikeTheOtherScenes) {
  // A small DPM scene (the shipped one at smoke scale takes ~2 min under ASan).
  std::ofstream(path("dpm.toml")) << "kind = \"dpm\"\nname = \"tiny\"\n"
                                     "[initial]\nd = 2\nn = 300\nnu = 0.3\nalpha = -3\nomega = 5\n"
                                     "[contact]\ncontact_time = 0.05\ndt_over_tc = 0.05\n"
                                     "[run]\nsteps = 200\nsample_every = 50\n[grids]\nreference_size = 10\n";
  const Result r = hgrid_run("run " + path("dpm.toml") + " --scale smoke --results " + path("res") + " --packings " +
                             path("cache"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("res/tiny-smoke.h5")));
  std::ifstream csv(path("res/tiny-smoke.csv"));
  std::string text((std::istreambuf_iterator<char>(csv)), {});
  for (const char* key : {"# n=300\n", "# steps=200\n", "# trajectories_identical=1\n", "# git_hash=",
                          "# optimal.sizes=", "# predicted_speedup_contact_detection=", "\nt,E_optimal,E_linked_cell,E_haff\n"})
    EXPECT_NE(text.find(key), std::string::npos) << key;
  EXPECT_EQ(text.find("paper"), std::string::npos) << "the paper's constants belong to plots/";
}

TEST_F(Cli, DpmSceneOnTwoThreadsRunsTheSameSimulation) {
  auto scene = [&](const std::string& name, const std::string& threads) {
    std::ofstream(path(name + ".toml")) << "kind = \"dpm\"\nname = \"" << name << "\"\n"
                                        << "[initial]\nd = 2\nn = 400\nnu = 0.4\nalpha = -3\nomega = 5\n"
                                           "[contact]\ncontact_time = 0.05\ndt_over_tc = 0.05\n"
                                           "[effects]\nfriction = true\n"
                                           "[run]\nsteps = 200\nsample_every = 50\nthreads = "
                                        << threads << "\n[grids]\nreference_size = 10\n";
    return hgrid_run("run " + path(name + ".toml") + " --scale smoke --results " + path("res") + " --packings " +
                     path("cache"));
  };
  auto energies = [&](const std::string& name) {  // the CSV's data lines
    std::ifstream csv(path("res/" + name + "-smoke.csv"));
    std::string line, out;
    while (std::getline(csv, line))
      if (!line.empty() && line[0] != '#') out += line + "\n";
    return out;
  };
  for (const auto& [name, threads] : {std::pair{"one", "1"}, std::pair{"two", "2"}}) {
    const Result r = scene(name, threads);
    ASSERT_EQ(r.status, 0) << r.err;
  }
  EXPECT_GT(energies("one").size(), 100u);
  EXPECT_EQ(energies("one"), energies("two"));
  const Result bad = scene("bad", "-1");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("run.threads"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(path("res/bad-smoke.csv")));
}

}  // namespace
}  // namespace hgrid::test
