// Calibration of K: the least-squares fit, error propagation, the stored
// record, and `K = "auto"` in scene files (no wall-clock assertions).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "hgridlab/calibration/calibrate.hpp"
#include "hgridlab/calibration/calibration.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/scenes/scene.hpp"

namespace hgrid {
namespace {

namespace fs = std::filesystem;

fs::path temp_path(const std::string& name) {
  return fs::temp_directory_path() / ("hgridlab_calib_" + std::to_string(::getpid()) + "_" + name);
}

/// Samples with varied N, A, C and W = c0 N + cc A + ct C times (1 + noise_i).
std::vector<CalibrationSample> manufactured(double c0, double cc, double ct, const std::vector<double>& noise) {
  std::vector<CalibrationSample> s;
  for (std::size_t i = 0; i < noise.size(); ++i) {
    CalibrationSample x;
    x.n = 20000 + 15000 * i;
    x.accesses = static_cast<std::uint64_t>(x.n * (5.0 + 7.0 * ((i * 7) % 5)));
    x.checks = static_cast<std::uint64_t>(x.n * (2.0 + 40.0 * ((i * 3) % 4)));
    x.seconds = (c0 * double(x.n) + cc * double(x.accesses) + ct * double(x.checks)) * (1 + noise[i]);
    s.push_back(x);
  }
  return s;
}

TEST(Calibrate, FitRecoversManufacturedCoefficientsExactly) {
  const double c0 = 12e-9, cc = 6.5e-9, ct = 2.5e-9;
  const auto s = manufactured(c0, cc, ct, std::vector<double>(9, 0.0));
  const Calibration c = fit_calibration(s);
  EXPECT_NEAR(c.c0 / c0, 1.0, 1e-10);
  EXPECT_NEAR(c.c_cell / cc, 1.0, 1e-10);
  EXPECT_NEAR(c.c_test / ct, 1.0, 1e-10);
  EXPECT_NEAR(c.K, cc / ct, 1e-9);
  EXPECT_LT(c.K_err, 1e-8);
  EXPECT_LT(c.c_cell_err, 1e-8 * cc);
  EXPECT_NEAR(c.r2, 1.0, 1e-12);
  EXPECT_EQ(c.points, 9);
  EXPECT_THROW(fit_calibration(std::vector<CalibrationSample>(s.begin(), s.begin() + 3)), std::invalid_argument);
}

TEST(Calibrate, RatioErrorPropagation) {
  // Independent: relative errors add in quadrature.
  Ratio r = ratio_with_error(6.0, 2.0, 0.3 * 0.3, 0.1 * 0.1, 0.0);
  EXPECT_DOUBLE_EQ(r.value, 3.0);
  EXPECT_NEAR(r.err, 3.0 * std::sqrt(0.05 * 0.05 + 0.05 * 0.05), 1e-12);
  // a = 3 b exactly (fully correlated): the ratio has no error.
  r = ratio_with_error(6.0, 2.0, 9 * 0.01, 0.01, 3 * 0.01);
  EXPECT_NEAR(r.err, 0.0, 1e-9);
  // Anti-correlated: larger than independent.
  EXPECT_GT(ratio_with_error(6.0, 2.0, 0.09, 0.01, -0.02).err, 3.0 * std::sqrt(0.005));
}

TEST(Calibrate, FitErrorsMatchTheNormalEquations) {
  const std::vector<double> noise = {0.03, -0.05, 0.02, 0.04, -0.01, -0.03, 0.05, -0.02, 0.01, 0.0};
  const auto s = manufactured(10e-9, 5e-9, 2e-9, noise);
  const Calibration c = fit_calibration(s);
  // Independently: rows x_i / W_i, target 1; M = X^T X (3x3), cov = s2 M^-1.
  double M[3][3] = {}, v[3] = {};
  for (const auto& x : s) {
    const double r[3] = {double(x.n) / x.seconds, double(x.accesses) / x.seconds, double(x.checks) / x.seconds};
    for (int a = 0; a < 3; ++a) {
      v[a] += r[a];
      for (int b = 0; b < 3; ++b) M[a][b] += r[a] * r[b];
    }
  }
  const auto det3 = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double D = det3(M);
  double coef[3];
  for (int k = 0; k < 3; ++k) {  // Cramer's rule
    double Mk[3][3];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) Mk[a][b] = b == k ? v[a] : M[a][b];
    coef[k] = det3(Mk) / D;
  }
  double chi2 = 0;
  for (const auto& x : s) {
    const double r = 1 - (coef[0] * double(x.n) + coef[1] * double(x.accesses) + coef[2] * double(x.checks)) / x.seconds;
    chi2 += r * r;
  }
  const double s2 = chi2 / double(s.size() - 3);
  // Inverse entries by cofactors: (M^-1)_11 = (M00 M22 - M02 M20) / D, etc.
  const double inv11 = (M[0][0] * M[2][2] - M[0][2] * M[2][0]) / D;
  const double inv22 = (M[0][0] * M[1][1] - M[0][1] * M[1][0]) / D;
  const double inv12 = -(M[0][0] * M[2][1] - M[0][1] * M[2][0]) / D;
  EXPECT_NEAR(c.c_cell / coef[1], 1.0, 1e-6);
  EXPECT_NEAR(c.c_test / coef[2], 1.0, 1e-6);
  EXPECT_NEAR(c.c_cell_err / std::sqrt(s2 * inv11), 1.0, 1e-5);
  EXPECT_NEAR(c.c_test_err / std::sqrt(s2 * inv22), 1.0, 1e-5);
  EXPECT_NEAR(c.cov_cell_test / (s2 * inv12), 1.0, 1e-5);
  const Ratio K = ratio_with_error(coef[1], coef[2], s2 * inv11, s2 * inv22, s2 * inv12);
  EXPECT_NEAR(c.K_err / K.err, 1.0, 1e-5);
  EXPECT_GT(c.K_err, 0.0);
  EXPECT_LT(c.r2, 1.0);
}

Calibration example() {
  Calibration c;
  c.K = 0.7312345678901234;
  c.K_err = 0.0412;
  c.c_cell = 3.1e-9, c.c_cell_err = 1.2e-10;
  c.c_test = 4.24e-9, c.c_test_err = 9e-11;
  c.c0 = 1.7e-8, c.c0_err = 2e-9;
  c.cov_cell_test = -1e-21;
  c.r2 = 0.987, c.rms_rel_residual = 0.08;
  c.points = 30;
  c.machine = "Test CPU";
  c.date = "2026-11-22T19:00:00Z";
  c.git_hash = "abc";
  c.compiler = "GNU 12";
  c.preset = "full";
  return c;
}

TEST(Calibrate, JsonRoundTrip) {
  const fs::path p = temp_path("dir") / "sub" / "calibration.json";
  const Calibration c = example();
  save_calibration(c, p.string());
  const Calibration r = load_calibration(p.string());
  EXPECT_EQ(r.K, c.K);  // exact: JSON keeps every digit of a double
  EXPECT_EQ(r.K_err, c.K_err);
  EXPECT_EQ(r.c_cell, c.c_cell);
  EXPECT_EQ(r.c_test_err, c.c_test_err);
  EXPECT_EQ(r.c0, c.c0);
  EXPECT_EQ(r.cov_cell_test, c.cov_cell_test);
  EXPECT_EQ(r.r2, c.r2);
  EXPECT_EQ(r.points, c.points);
  EXPECT_EQ(r.machine, c.machine);
  EXPECT_EQ(r.date, c.date);
  EXPECT_EQ(r.git_hash, c.git_hash);
  EXPECT_EQ(r.compiler, c.compiler);
  EXPECT_EQ(r.preset, c.preset);
  fs::remove_all(temp_path("dir"));
}

TEST(Calibrate, PathFromEnvironment) {
  ::setenv("HGRID_CALIBRATION", "/some/where/k.json", 1);
  EXPECT_EQ(calibration_path(), "/some/where/k.json");
  ::unsetenv("HGRID_CALIBRATION");
  ::setenv("XDG_CONFIG_HOME", "/cfg", 1);
  EXPECT_EQ(calibration_path(), "/cfg/hgridlab/calibration.json");
  ::unsetenv("XDG_CONFIG_HOME");
  ::setenv("HOME", "/home/u", 1);
  EXPECT_EQ(calibration_path(), "/home/u/.config/hgridlab/calibration.json");
}

/// The InputError's field and message of f(), or "" if it did not throw.
template <class F>
std::pair<std::string, std::string> input_error(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return {e.field(), e.what()};
  }
  return {"", ""};
}

TEST(Calibrate, MissingOrCorruptFileNamesFieldAndPath) {
  const fs::path p = temp_path("bad.json");
  ::setenv("HGRID_CALIBRATION", p.c_str(), 1);
  fs::remove(p);
  auto [field, msg] = input_error([] { resolve_K("auto", "K"); });
  EXPECT_EQ(field, "K");
  EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("hgrid calibrate"), std::string::npos) << msg;
  for (const char* text : {"{not json", "[]", "{\"format\": \"hgridlab-calibration-1\"}",
                           "{\"format\": \"other\", \"K\": 1}"}) {
    std::ofstream(p) << text;
    std::tie(field, msg) = input_error([] { resolve_K("auto", "K"); });
    EXPECT_EQ(field, "K") << text;
    EXPECT_NE(msg.find("not a valid calibration"), std::string::npos) << msg;
    EXPECT_EQ(input_error([&] { load_calibration(p.string()); }).first, "calibration");
  }
  Calibration c = example();
  c.K = -1;  // a stored K must be > 0
  save_calibration(c, p.string());
  EXPECT_EQ(input_error([] { resolve_K("auto", "K"); }).first, "K");
  fs::remove(p);
}

TEST(Calibrate, NumericKUnchanged) {
  EXPECT_EQ(resolve_K("0.2", "K"), 0.2);
  EXPECT_EQ(resolve_K("3", "K"), 3.0);
  EXPECT_EQ(resolve_K("0", "K"), 0.0);
  for (const char* bad : {"", "-1", "nan", "inf", "0.2x", "Auto"})
    EXPECT_EQ(input_error([&] { resolve_K(bad, "K"); }).first, "K") << bad;
}

TEST(Calibrate, SceneGridKAuto) {
  const fs::path cal = temp_path("scene_cal.json"), scene = temp_path("scene.toml");
  std::ofstream(scene) << "name = \"t\"\n[packings]\nn = 100\nnu = 0.2\n[grid]\nK = \"auto\"\n";
  ::setenv("HGRID_CALIBRATION", cal.c_str(), 1);
  fs::remove(cal);
  const auto [field, msg] = input_error([&] { load_scene(scene.string(), "default"); });
  EXPECT_EQ(field, "grid.K");
  EXPECT_NE(msg.find(cal.string()), std::string::npos) << msg;
  save_calibration(example(), cal.string());
  EXPECT_EQ(load_scene(scene.string(), "default").grid.K, example().K);
  std::ofstream(scene) << "name = \"t\"\n[packings]\nn = 100\nnu = 0.2\n[grid]\nK = \"fast\"\n";
  EXPECT_EQ(input_error([&] { load_scene(scene.string(), "default"); }).first, "grid.K");
  fs::remove(cal);
  fs::remove(scene);
}

TEST(Calibrate, SceneListCoversTheRequestedRange) {
  for (bool quick : {false, true}) {
    const auto scenes = calibration_scenes(quick);
    EXPECT_GE(scenes.size(), 12u);
    bool d2 = false, d3 = false, excl = false, single = false, a0 = false, a3 = false, bed = false;
    for (const auto& s : scenes) {
      d2 |= s.packing.d == 2, d3 |= s.packing.d == 3, excl |= s.packing.placement == Placement::excluded;
      single |= s.cells == "single", a0 |= s.packing.alpha == 0, a3 |= s.packing.alpha == -3;
      // A settled bed's regime (docs/MODEL.md section 9): a linked cell over
      // dense 3D hard spheres of uniform diameters and a moderate size ratio.
      bed |= s.packing.d == 3 && s.packing.placement == Placement::excluded && s.packing.nu >= 0.5 &&
             s.packing.alpha == 0 && s.packing.omega <= 5 && s.cells == "single";
      EXPECT_GE(s.packing.n, 10000u);  // down to the DPM test's N = 10^4 (quick)
      EXPECT_LE(s.packing.n, 200000u);
    }
    EXPECT_TRUE(d2 && d3 && excl && single && a0 && a3 && bed);
  }
}

}  // namespace
}  // namespace hgrid
