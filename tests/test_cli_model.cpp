// End-to-end: `hgrid model --json` and its bad-input exit status.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/wait.h>

namespace {
struct Run {
  int status;
  std::string out;
};
Run run(const std::string& args) {
  const std::string cmd = std::string(HGRID_BINARY) + " " + args + " 2>/dev/null";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}
}  // namespace

TEST(CliModel, JsonLinearPaperCase) {
  const auto r = run("model --d 3 --nu 0.7 --alpha -3 --omega 100 --K 0.2 --search topdown --cells linear --json");
  ASSERT_EQ(r.status, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["levels"], 43);
  EXPECT_EQ(j["sizes"].size(), 43u);
  EXPECT_NEAR(j["sizes"].back().get<double>(), 200.0, 1e-9);  // units of r_min
  EXPECT_NEAR(j["T_over_N"].get<double>(),
              j["T_cd_over_N"].get<double>() + 0.2 * j["T_ca_over_N"].get<double>(), 1e-9);
}

TEST(CliModel, FixedLevelsAndBadInputs) {
  const auto r = run("model --cells optimal --levels 5 --json");
  ASSERT_EQ(r.status, 0);
  EXPECT_EQ(nlohmann::json::parse(r.out)["levels"], 5);
  for (const char* bad : {"model --omega 0.5", "model --nu 0", "model --levels 0", "model --q -1 --cells constant",
                          "model --nu nan", "model --cells cubic", "model --search sideways"})
    EXPECT_EQ(run(bad).status, 2) << bad;
  EXPECT_EQ(run("model --help").status, 0);
  EXPECT_EQ(run("modelfigs --help").status, 0);
}

TEST(CliModel, ExcludedPlacement) {
  // Same sizes, two models; in 2D up to omega = 50.
  const auto r = run("model --nu 0.6 --alpha -3 --omega 10 --placement excluded --json");
  ASSERT_EQ(r.status, 0);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["params"]["placement"], "excluded");
  EXPECT_GT(j["T_over_N"].get<double>(), 0.0);
  EXPECT_NE(j["T_over_N"].get<double>(), j["T_over_N_random"].get<double>());
  const auto discs = run("model --d 2 --nu 0.4 --alpha -3 --omega 10 --placement excluded --json");
  ASSERT_EQ(discs.status, 0);
  EXPECT_LT(nlohmann::json::parse(discs.out)["T_over_N"].get<double>(),
            nlohmann::json::parse(discs.out)["T_over_N_random"].get<double>());
  for (const char* bad : {"model --d 2 --omega 100 --placement excluded", "model --placement dense",
                          "model --excluded-sizes", "model --omega 1e6 --placement excluded"})
    EXPECT_EQ(run(bad).status, 2) << bad;
}
