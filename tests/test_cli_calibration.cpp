// End to end: `--K auto` in `hgrid model` and `hgrid count` against a stored
// calibration (HGRID_CALIBRATION), and exit status 2 without one.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "hgridlab/calibration/calibration.hpp"

namespace {

using hgrid::test::hgrid_run;
using hgrid::test::Result;
namespace fs = std::filesystem;

fs::path temp_path(const std::string& name) {
  return fs::temp_directory_path() / ("hgridlab_cli_calib_" + std::to_string(::getpid()) + "_" + name);
}

/// Runs hgrid with HGRID_CALIBRATION=cal; stdout and stderr captured.
Result run(const fs::path& cal, const std::string& args) {
  return hgrid_run(args, "HGRID_CALIBRATION='" + cal.string() + "'");
}

class CliCalibration : public ::testing::Test {
 protected:
  void SetUp() override {
    cal_ = temp_path("cal.json");
    hgrid::Calibration c;
    c.K = 1.75, c.K_err = 0.1, c.c_cell = 3.5e-9, c.c_test = 2e-9, c.points = 12, c.preset = "test";
    hgrid::save_calibration(c, cal_.string());
  }
  void TearDown() override { fs::remove(cal_); }
  fs::path cal_;
};

TEST_F(CliCalibration, ModelAutoEqualsNumericK) {
  const std::string base = "model --d 3 --nu 0.5 --alpha -3 --omega 50 --cells optimal --json";
  const Result a = run(cal_, base + " --K auto"), n = run(cal_, base + " --K 1.75");
  ASSERT_EQ(a.status, 0) << a.err;
  ASSERT_EQ(n.status, 0) << n.err;
  EXPECT_EQ(a.out, n.out);
  EXPECT_EQ(nlohmann::json::parse(a.out)["params"]["K"], 1.75);
  // Not the paper's K: the sizes differ from the default K = 0.2.
  EXPECT_NE(a.out, run(cal_, base).out);
}

TEST_F(CliCalibration, CountAutoEqualsNumericK) {
  const fs::path pk = temp_path("p.h5");
  ASSERT_EQ(run(cal_, "generate --d 3 --n 3000 --nu 0.3 --alpha -3 --omega 10 --seed 3 --out " + pk.string()).status,
            0);
  const std::string base = "count " + pk.string() + " --cells optimal --json";
  const Result a = run(cal_, base + " --K auto"), n = run(cal_, base + " --K 1.75");
  ASSERT_EQ(a.status, 0) << a.err;
  ASSERT_EQ(n.status, 0) << n.err;
  auto ja = nlohmann::json::parse(a.out), jn = nlohmann::json::parse(n.out);
  for (auto* j : {&ja, &jn}) j->erase("seconds_build"), j->erase("seconds_query");
  EXPECT_EQ(ja, jn);
  EXPECT_EQ(ja["K"], 1.75);
  // --repeat adds the fastest uncounted times and leaves the counts alone.
  const Result t = run(cal_, base + " --K auto --repeat 2");
  ASSERT_EQ(t.status, 0) << t.err;
  const auto jt = nlohmann::json::parse(t.out);
  EXPECT_EQ(jt["cell_accesses"], ja["cell_accesses"]);
  EXPECT_EQ(jt["repeats"], 2);
  EXPECT_GT(jt["seconds_query_best"].get<double>(), 0.0);
  fs::remove(pk);
}

TEST_F(CliCalibration, MissingOrCorruptCalibrationExits2NamingK) {
  const fs::path missing = temp_path("nowhere.json");
  for (const char* args : {"model --K auto", "model --cells optimal --K auto --json"}) {
    const Result r = run(missing, args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_TRUE(r.out.empty());
    EXPECT_NE(r.err.find("K: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("hgrid calibrate"), std::string::npos) << r.err;
  }
  std::ofstream(cal_) << "{ \"format\": \"hgridlab-calibration-1\", \"K\": ";
  const Result r = run(cal_, "model --K auto");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("K: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not a valid calibration"), std::string::npos) << r.err;
  EXPECT_EQ(run(cal_, "model --K fast").status, 2);
  EXPECT_EQ(run(cal_, "model --K -1").status, 2);
  EXPECT_EQ(run(cal_, "calibrate --help").status, 0);
}

}  // namespace
