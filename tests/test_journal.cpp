// The resume journal: every journal of a stem (one per MPI rank) is read, a
// result with several levels comes back whole, and a finished run removes
// them all.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "hgridlab/scenes/journal.hpp"
#include "hgridlab/scenes/result_files.hpp"
#include "hgridlab/scenes/runner.hpp"
#include "hgridlab/scenes/run_scene.hpp"
#include "hgridlab/base/error.hpp"
#include "cli_support.hpp"
#include "hgridlab/mpi/comm.hpp"
#include "hgridlab/mpi/sweep.hpp"

namespace hgrid {
namespace {

namespace fs = std::filesystem;

class Journal : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("hgridlab_journal_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    opt_.results_dir = (dir_ / "res").string();
    opt_.packing_dir = (dir_ / "packings").string();
    opt_.progress = false;
    // Wide radii, so that every point has several levels.
    scene_ = load_scene_text(
        "name = \"j\"\n[packings]\nn = 1500\nnu = 0.3\nomega = 50\nseeds = [1, 2]\n"
        "[grid]\nsearch = [\"topdown\", \"bottomup\"]\n",
        "default", "j.toml");
  }
  void TearDown() override { fs::remove_all(dir_); }

  static void expect_same_counts(const std::vector<PointResult>& a, const std::vector<PointResult>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].m.counts.accesses_by_level, b[i].m.counts.accesses_by_level) << i;
      EXPECT_EQ(a[i].m.counts.checks_by_level, b[i].m.counts.checks_by_level) << i;
      EXPECT_EQ(a[i].m.sizes, b[i].m.sizes) << i;
      EXPECT_EQ(a[i].m.T_over_N, b[i].m.T_over_N) << i;
    }
  }

  fs::path dir_;
  RunOptions opt_;
  Scene scene_;
};

TEST_F(Journal, PathsPerRank) {
  EXPECT_EQ(journal_path("res/j"), "res/j.journal.jsonl");
  EXPECT_EQ(journal_path("res/j", 3), "res/j.journal.rank3.jsonl");
  fs::create_directories(opt_.results_dir);
  const std::string stem = result_stem(scene_, opt_);
  for (const char* name : {"j.journal.jsonl", "j.journal.rank2.jsonl", "j.journal.rank10.jsonl",
                           "j-smoke.journal.rank1.jsonl", "j.journal.rankx.jsonl", "j.journal.rank.jsonl"})
    std::ofstream(dir_ / "res" / name) << "\n";
  const auto files = journal_files(stem);
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0], journal_path(stem));  // rank 0's first
  remove_journals(stem);
  EXPECT_TRUE(journal_files(stem).empty());
  EXPECT_TRUE(fs::exists(dir_ / "res" / "j-smoke.journal.rank1.jsonl"));  // another scale's
}

TEST_F(Journal, EveryRanksJournalIsReusedWithAllItsLevels) {
  const std::vector<PointResult> first = run_scene(scene_, opt_);
  ASSERT_EQ(first.size(), 4u);
  for (const auto& r : first) ASSERT_GT(r.m.counts.levels, 1);
  const std::string stem = result_stem(scene_, opt_);
  EXPECT_TRUE(journal_files(stem).empty());

  // As a 3-rank run killed after three points leaves it (rank 1 measured
  // nothing), plus a line of another scene text.
  JournalWriter(journal_path(stem, 0), scene_.source).append(first[0]);
  {
    JournalWriter rank2(journal_path(stem, 2), scene_.source);
    rank2.append(first[2]);
    rank2.append(first[3]);
  }
  JournalWriter(journal_path(stem, 5), "another scene").append(first[1]);
  const Resumed resumed = resume(scene_, stem, false);
  EXPECT_EQ(resumed.todo, std::vector<std::size_t>{1});
  expect_same_counts({resumed.results[0], resumed.results[2], resumed.results[3]}, {first[0], first[2], first[3]});

  const std::vector<PointResult> again = run_scene(scene_, opt_);
  expect_same_counts(again, first);
  EXPECT_TRUE(journal_files(stem).empty());
}

TEST_F(Journal, ResultLinesRoundTripExactly) {
  opt_.packing_dir = (dir_ / "p").string();
  const PointResult r = run_point(scene_, scene_.points[1], opt_);
  const PointResult back = result_from_json_line(result_json_line(r), scene_.grid.K);
  expect_same_counts({back}, {r});
  EXPECT_EQ(back.m.model_T_over_N, r.m.model_T_over_N);
  EXPECT_EQ(back.m.seconds_query, r.m.seconds_query);
  EXPECT_THROW(result_from_json_line(result_json_line(r), scene_.grid.K * 2), InputError);  // T/N disagrees
}

TEST_F(Journal, GroupsKeepAPackingOnOneRankAndBalanceTheWork) {
  const auto groups = group_by_packing(scene_, {0, 1, 2, 3});
  ASSERT_EQ(groups.size(), 2u);  // two seeds, two searches each
  EXPECT_EQ(groups[0], (std::vector<std::size_t>{0, 1}));
  // Five groups of 1, 1, 3, 1, 2 points of one n: the largest first, each
  // to the rank with the least work so far.
  Scene s = scene_;
  const ScenePoint p = s.points[0];
  s.points.assign(8, p);
  const std::vector<std::vector<std::size_t>> five{{0}, {1}, {2, 3, 4}, {5}, {6, 7}};
  EXPECT_EQ(assign_groups(s, five, 2), (std::vector<int>{1, 0, 0, 1, 1}));
  EXPECT_EQ(assign_groups(s, five, 1), (std::vector<int>{0, 0, 0, 0, 0}));
  EXPECT_EQ(assign_groups(s, five, 8), (std::vector<int>{2, 3, 0, 4, 1}));
}

TEST_F(Journal, OneRankSweepIsTheSerialRun) {
  const std::vector<PointResult> serial = run_scene(scene_, opt_);
  opt_.results_dir = (dir_ / "res1").string();
  expect_same_counts(mpi::run_scene_on_ranks(scene_, opt_), serial);
  EXPECT_TRUE(fs::exists(dir_ / "res1" / "j.csv"));
}

// Scenes run together in one pool write what each writes alone; a packing
// two of them share is made once; a scene measured before (its journal)
// is resumed, not measured again.
TEST_F(Journal, ScenesInOnePoolAreEachSceneAlone) {
  const Scene other = load_scene_text(
      "name = \"k\"\n[packings]\nn = 1500\nnu = [0.3, 0.2]\nomega = 50\nseeds = [2]\n[grid]\nsearch = \"topdown\"\n",
      "default", "k.toml");
  const std::vector<PointResult> alone_j = run_scene(scene_, opt_), alone_k = run_scene(other, opt_);
  opt_.results_dir = (dir_ / "pooled").string();
  opt_.packing_dir = (dir_ / "pooled_packings").string();
  opt_.jobs = 2;
  const auto pooled = run_scenes({scene_, other}, opt_);
  ASSERT_EQ(pooled.size(), 2u);
  expect_same_counts(pooled[0], alone_j);
  expect_same_counts(pooled[1], alone_k);
  for (const char* f : {"j.csv", "j.h5", "k.csv", "k.h5"}) EXPECT_TRUE(fs::exists(dir_ / "pooled" / f)) << f;
  EXPECT_TRUE(journal_files(result_stem(scene_, opt_)).empty());
  // Packings: j's seeds 1 and 2 at nu = 0.3, k's nu = 0.2 (its nu = 0.3 is j's seed 2).
  std::size_t packings = 0;
  for (const auto& e : fs::directory_iterator(opt_.packing_dir)) packings += e.path().extension() == ".h5";
  EXPECT_EQ(packings, 3u);
  // Two scenes with the same result files are refused.
  EXPECT_THROW(run_scenes({scene_, scene_}, opt_), InputError);
}

}  // namespace
}  // namespace hgrid

namespace hgrid::test {
namespace {

// A build without MPI started by mpirun as several ranks refuses to run P
// copies of the same work (the MPI build is covered by tests/mpi/*.sh; it
// would try to reach a launcher that is not there).
TEST(MpiLaunch, BuildWithoutMpiRefusesSeveralRanks) {
  if (mpi::built_with_mpi()) GTEST_SKIP() << "this build has MPI";
  const Result r = hgrid_run("--version", "OMPI_COMM_WORLD_SIZE=2 OMPI_COMM_WORLD_RANK=0");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("built without MPI"), std::string::npos) << r.err;
  EXPECT_EQ(hgrid_run("--version", "OMPI_COMM_WORLD_SIZE=1").status, 0);
}

}  // namespace
}  // namespace hgrid::test
