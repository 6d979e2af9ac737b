// Scene files: expansion, scale overrides, and rejected input naming the key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "hgridlab/base/error.hpp"
#include "hgridlab/packing/identity.hpp"
#include "hgridlab/scenes/scene.hpp"

namespace hgrid {
namespace {

namespace fs = std::filesystem;

std::string write_scene(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("hgridlab_scene_" + std::to_string(::getpid()) + "_" + name + ".toml");
  std::ofstream(p) << text;
  return p.string();
}

const char* kBase = R"(
name = "t"
[packings]
n = [100, 200]
nu = [0.1, 0.2, 0.3]
alpha = -3
omega = [10, 100]
placement = ["random", "excluded"]
[grid]
search = ["topdown", "bottomup"]
[scale.smoke.packings]
n = 10
nu = 0.5
)";

TEST(Scene, ExpandsTheProduct) {
  const Scene s = load_scene(write_scene("base", kBase), "default");
  EXPECT_EQ(s.points.size(), 2u * 3 * 2 * 2 * 2);
  EXPECT_EQ(s.name, "t");
  EXPECT_EQ(s.grid.cells, CellMethod::optimal);
  EXPECT_DOUBLE_EQ(s.grid.K, 0.2);
  EXPECT_EQ(s.points[0].packing.d, 3);
  EXPECT_EQ(s.points[0].packing.boundary, Boundary::periodic);
}

TEST(Scene, ScaleOverridesPackingKeys) {
  const Scene s = load_scene(write_scene("smoke", kBase), "smoke");
  ASSERT_EQ(s.points.size(), 1u * 1 * 2 * 2 * 2);
  EXPECT_EQ(s.points[0].packing.n, 10u);
  EXPECT_DOUBLE_EQ(s.points[0].packing.nu, 0.5);
  // A scale the file does not mention is the base scene.
  EXPECT_EQ(load_scene(write_scene("paper", kBase), "paper").points.size(), 48u);
}

void expect_error_naming(const std::string& text, const std::string& key, const std::string& scale = "default") {
  try {
    load_scene(write_scene("bad", text), scale);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

TEST(Scene, RejectsBadInput) {
  expect_error_naming("name = \"t\"\ncolour = 1\n[packings]\nn = 1\nnu = 0.1\n", "colour");
  expect_error_naming("name = \"t\"\n[packings]\nn = 1\nnu = 0.1\nomgea = 3\n", "packings.omgea");
  expect_error_naming("name = \"t\"\n[packings]\nn = 1\nnu = 0\n", "packings.nu");
  expect_error_naming("name = \"t\"\n[packings]\nn = 1\nnu = 1.5\n", "packings.nu");
  expect_error_naming("name = \"t\"\n[packings]\nn = 1\nnu = 0.1\nomega = 0.5\n", "packings.omega");
  expect_error_naming("name = \"t\"\n[packings]\nn = 1\nnu = nan\n", "packings.nu");
  expect_error_naming("name = \"t\"\n[packings]\nn = 0\nnu = 0.1\n", "packings.n");
  expect_error_naming("name = \"t\"\n[packings]\nnu = 0.1\n", "packings.n");
  // Integers are integers: a float (even a whole one) is refused, naming the key.
  expect_error_naming("name = \"t\"\n[packings]\nn = 1e5\nnu = 0.1\n", "packings.n");
  expect_error_naming("name = \"t\"\n[packings]\nn = 10\nnu = 0.1\nseeds = [1, 2.0]\n", "packings.seeds");
  expect_error_naming("name = \"t\"\n[packings]\nn = 10\nnu = 0.1\nseeds = -1\n", "packings.seeds");
  expect_error_naming("name = \"t\"\n[packings]\nn = 10\nnu = 0.1\nd = 3.0\n", "packings.d");
  expect_error_naming("name = \"t\"\n[packings]\nn = 10\nnu = 0.1\n[grid]\nlevels = 2.5\n", "grid.levels");
  expect_error_naming("name = \"t\"\n[packings]\nn = 1\nnu = 0.1\nplacement = \"lattice\"\n", "packings.placement");
  expect_error_naming("name = \"t\"\n[packings]\nn = 1\nnu = 0.1\nboundary = \"open\"\n", "boundary");
  expect_error_naming("name = \"t\"\n[packings]\nn = 1\nnu = 0.1\n[grid]\ncells = \"magic\"\n", "grid.cells");
  expect_error_naming("name = \"t\"\n[packings]\nn = 1\nnu = 0.1\n[grid]\nsearch = \"sideways\"\n", "grid.search");
  expect_error_naming("name = \"t\"\n[packings]\nn = 1\nnu = 0.1\n[grid]\nK = -1\n", "grid.K");
  expect_error_naming("name = \"t\"\n[packings]\nn = 1\nnu = 0.1\n[record]\nvelocities = true\n", "record.velocities");
  expect_error_naming("name = \"t\"\n[packings]\nn = 1\nnu = 0.1\n[scale.huge.packings]\nn = 2\n", "scale.huge");
  expect_error_naming("name = \"t\"\n[packings]\nn = 1\nnu = 0.1\n", "scale", "huge");
  expect_error_naming("name = \"t\"\n[packings\nn = 1\n", "scene");
  expect_error_naming("[packings]\nn = 1\nnu = 0.1\n", "name");
  expect_error_naming("name = \"a/b\"\n[packings]\nn = 1\nnu = 0.1\n", "name");
  const std::string excluded = "name = \"t\"\n[packings]\nn = 10\nnu = 0.1\nplacement = \"excluded\"\n";
  expect_error_naming(excluded + "sweeps = 5\n", "packings.sweeps");
  expect_error_naming(excluded + "equilibrate = true\nsweeps = 0\n", "packings.sweeps");
  expect_error_naming(excluded + "equilibrate = true\nsweeps = 2.5\n", "packings.sweeps");
  expect_error_naming(excluded + "stop = \"stationary\"\n", "packings.stop");
  expect_error_naming(excluded + "equilibrate = true\nstop = \"soon\"\n", "packings.stop");
  expect_error_naming(excluded + "method = \"shake\"\n", "packings.method");
  expect_error_naming("name = \"t\"\n[packings]\nn = 10\nnu = 0.1\nmethod = \"growth\"\n", "packings.method");
  expect_error_naming("name = \"t\"\n[packings]\nn = 10\nnu = 0.1\nequilibrate = true\n", "packings.equilibrate");
}

TEST(Scene, PlacementMethodReachesTheExcludedPackingsOnly) {
  const Scene s = load_scene(write_scene("method", "name = \"t\"\n[packings]\nn = 10\nnu = 0.1\nplacement = "
                                                   "[\"excluded\", \"random\"]\nmethod = \"growth\"\n"),
                             "default");
  ASSERT_EQ(s.points.size(), 2u);
  EXPECT_EQ(s.points[0].packing.method, ExcludedMethod::growth);
  EXPECT_EQ(s.points[1].packing.method, ExcludedMethod::automatic);
  auto other = s.points[0].packing;
  other.method = ExcludedMethod::automatic;
  EXPECT_NE(packing_key(other), packing_key(s.points[0].packing));
}

TEST(Scene, EquilibrationSweepsReachThePackings) {
  const std::string excluded = "name = \"t\"\n[packings]\nn = 10\nnu = 0.1\nplacement = \"excluded\"\nequilibrate = true\n";
  EXPECT_EQ(load_scene(write_scene("eq", excluded), "default").points.at(0).packing.sweeps, kDefaultEquilibrationSweeps);
  const Scene s = load_scene(write_scene("eq", excluded + "sweeps = 300\n"), "default");
  EXPECT_TRUE(s.points.at(0).packing.equilibrate);
  EXPECT_EQ(s.points.at(0).packing.sweeps, 300);
  // Beside random centres (figure 11's two placements): only the excluded-volume packings are equilibrated.
  const Scene both = load_scene(write_scene("eq", "name = \"t\"\n[packings]\nn = 10\nnu = 0.1\nplacement = "
                                                  "[\"excluded\", \"random\"]\nequilibrate = true\nsweeps = 300\n"),
                                "default");
  ASSERT_EQ(both.points.size(), 2u);
  EXPECT_TRUE(both.points[0].packing.equilibrate);
  EXPECT_EQ(both.points[0].packing.sweeps, 300);
  EXPECT_FALSE(both.points[1].packing.equilibrate);
  EXPECT_NO_THROW(check_packing_spec(both.points[1].packing));
  // stop = "stationary": the sweeps are the cap; another packing than a run of fixed sweeps.
  const Scene until = load_scene(write_scene("eq", excluded + "sweeps = 300\nstop = \"stationary\"\n"), "default");
  EXPECT_EQ(until.points.at(0).packing.stop, EquilibrationStop::stationary);
  EXPECT_EQ(until.points.at(0).packing.sweeps, 300);
  EXPECT_EQ(s.points.at(0).packing.stop, EquilibrationStop::sweeps);
  EXPECT_NE(packing_key(until.points.at(0).packing), packing_key(s.points.at(0).packing));
}

// [[packings.groups]]: each group is [packings] with some keys replaced;
// their points follow one another, and a scale's override reaches every group.
TEST(Scene, GroupsReplaceKeysOfThePackings) {
  const std::string text = R"(
name = "t"
[packings]
n = 100
nu = [0.1, 0.2]
omega = [2, 10, 50]
placement = ["excluded", "random"]
equilibrate = true
moves = "event-chain"
stop = "stationary"
stationary_tol = 0.0025
[[packings.groups]]
omega = [2, 10]
method = "growth"
[[packings.groups]]
omega = 50
[scale.smoke.packings]
nu = 0.3
)";
  const Scene s = load_scene(write_scene("groups", text), "default");
  ASSERT_EQ(s.points.size(), 2u * 2 * 2 + 1u * 2 * 2);
  EXPECT_DOUBLE_EQ(s.points[0].packing.omega, 2);
  EXPECT_EQ(s.points[0].packing.method, ExcludedMethod::growth);
  EXPECT_EQ(s.points[0].packing.moves, EquilibrationMoves::event_chain);
  EXPECT_DOUBLE_EQ(s.points[0].packing.stationary_tol, 0.0025);
  EXPECT_DOUBLE_EQ(s.points.back().packing.omega, 50);
  EXPECT_EQ(s.points[8].packing.method, ExcludedMethod::automatic);
  for (const auto& pt : s.points)  // random centres are not equilibrated
    EXPECT_EQ(pt.packing.equilibrate, pt.packing.placement == Placement::excluded);
  const Scene smoke = load_scene(write_scene("groups", text), "smoke");
  ASSERT_EQ(smoke.points.size(), 2u * 2 + 1u * 2);
  for (const auto& pt : smoke.points) EXPECT_DOUBLE_EQ(pt.packing.nu, 0.3);
  const std::string head = "name = \"t\"\n[packings]\nn = 10\nnu = 0.1\nplacement = \"excluded\"\n";
  expect_error_naming(head + "groups = 3\n", "packings.groups");
  expect_error_naming(head + "[[packings.groups]]\ncolour = 1\n", "packings.groups[0].colour");
  expect_error_naming(head + "stationary_tol = 0.01\n", "packings.stationary_tol");
  expect_error_naming(head + "moves = \"event-chain\"\n", "packings.moves");
  expect_error_naming(head + "equilibrate = true\nmoves = \"event-chain\"\nboundary = \"walls\"\n", "packings.moves");
}

TEST(Scene, KindSelectsTheRunner) {
  EXPECT_EQ(scene_kind(write_scene("kind", kBase)), "contact");
  EXPECT_EQ(scene_kind(std::string(HGRID_SOURCE_DIR) + "/experiments/dpm_free_cooling.toml"), "dpm");
  expect_error_naming(std::string("kind = \"dpm\"\n") + kBase, "kind");
  try {
    scene_kind(write_scene("badkind", std::string("kind = \"md\"\n") + kBase));
    ADD_FAILURE() << "unknown kind accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("kind"), std::string::npos);
  }
}

TEST(Scene, ShippedScenesLoad) {
  for (const auto& e : fs::directory_iterator(fs::path(HGRID_SOURCE_DIR) / "experiments")) {
    if (e.path().extension() != ".toml") continue;
    if (scene_kind(e.path().string()) != "contact") continue;  // DPM scenes: tests/test_dpm.cpp
    for (const char* scale : {"smoke", "default", "paper"}) {
      SCOPED_TRACE(e.path().string() + " " + scale);
      EXPECT_NO_THROW(load_scene(e.path().string(), scale));
    }
  }
}

}  // namespace
}  // namespace hgrid
