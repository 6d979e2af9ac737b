// The cost model over a packing's density field (model/density_field.hpp,
// advice recommend_for_field; docs/MODEL.md section 14), checked against what
// the counted grid measures on beds LAMMPS and MercuryDPM poured
// (tests/data/beds, made by experiments/beds/make_fixtures.sh and
// make_mercurydpm_fixtures.sh) and on homogeneous packings.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_support.hpp"
#include "hgridlab/advice/recommend.hpp"
#include "hgridlab/io/particle_file.hpp"
#include "hgridlab/measure/measurement.hpp"
#include "hgridlab/model/density_field.hpp"
#include "hgridlab/packing/generate.hpp"
#include "support.hpp"

namespace hgrid::test {
namespace {

const std::string kBeds = std::string(HGRID_SOURCE_DIR) + "/tests/data/beds/";
const std::string kNoCalibration = "HGRID_CALIBRATION=/nonexistent/calibration.json";

/// The targets on poured beds, with no calibration: the recommended sizes measure
/// within this of the best of the scan ...
constexpr double kBestOfScanRelTol = 0.05;
/// ... and the field model's T/N is within this of what they measure.
constexpr double kPredictionRelTol = 0.10;
/// Halving or doubling the field's bins moves its prediction by less than this.
constexpr double kResolutionRelTol = 0.01;
/// Random centres in a periodic box: F = 1 up to counting noise (N = 20 000;
/// level pairs holding at least 5 % of the count: measured 0.3-1.2 %).
constexpr double kUniformFRelTol = 0.02;
/// The scan: the model's sizes for these nu, and the linked cell.
constexpr double kScanNu[] = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7};

constexpr double kK = 0.2;

double measured(const Packing& p, const std::vector<double>& sizes) {
  return measure(p, GridParams{sizes, Search::top_down}).T_over_N;
}

DensityField field_of(const ParticleSet& s, const FieldOptions& opt = {}) {
  return DensityField(s.positions, s.radii, FieldBox{s.d, *s.box, s.periodic_per_axis()}, opt);
}

struct Bed {
  const char* file;
  int frame;  // 0: in progress (a gas over a bed), 1: settled
};
/// LAMMPS's beds (bed*.dump, experiments/beds/make_fixtures.sh) and
/// MercuryDPM's (mdpm*.data, experiments/beds/make_mercurydpm_fixtures.sh).
constexpr Bed kBedsUsed[] = {{"bed3d_o5_s1.dump", 0},    {"bed3d_o5_s1.dump", 1},   {"bed3d_o3_s2.dump", 0},
                             {"bed3d_o3_s2.dump", 1},    {"bed2d_o5_s1.dump", 0},   {"bed2d_o5_s1.dump", 1},
                             {"bed2d_o10_s2.dump", 0},   {"bed2d_o10_s2.dump", 1},  {"mdpm3d_o5_s1.data", 0},
                             {"mdpm3d_o5_s1.data", 1},   {"mdpm2d_o10_s2.data", 0}, {"mdpm2d_o10_s2.data", 1}};

/// A bed as poured: a MercuryDPM .data file does not say its boundary; the
/// driver walled every side.
ParticleSet read_bed(const Bed& b) {
  ParticleSet s = read_particles(kBeds + b.file, Isolation::none, b.frame);
  if (std::string(b.file).ends_with(".data")) s.boundary = Boundary::walls;
  return s;
}

TEST(DensityField, UniformCentresInAPeriodicBoxGiveTheBoxModel) {
  constexpr std::uint64_t kSeed = 5;
  const Scene<3> s = random_scene<3>(20000, 0.3, -3, 5, Boundary::periodic, kSeed);
  std::vector<double> x, r;
  for (const auto& p : s.spheres) {
    r.push_back(p.r);
    for (double c : p.x) x.push_back(c);
  }
  const DensityField f(x, r, FieldBox{3, s.box, {true, true, true}});
  const Empirical dist(r);
  const std::vector<double> sizes = recommend_cell_sizes(r, ModelParams{3, f.box_nu(), kK}).sizes;
  const std::vector<double> F = f.factors(ModelParams{3, f.box_nu(), kK}, sizes);
  const ModelResult m = evaluate_model(dist, ModelParams{3, f.box_nu(), kK}, sizes);
  for (std::size_t at = 0; at < F.size(); ++at)
    if (m.T_cd_pair[at] > 0.05 * m.T_cd_over_N) {
      EXPECT_NEAR(F[at], 1.0, kUniformFRelTol) << "pair " << at << " seed " << kSeed;
    }
  EXPECT_NEAR(f.evaluate(ModelParams{3, 0.3, kK}, sizes).model.T_over_N, m.T_over_N, kUniformFRelTol * m.T_over_N);
  EXPECT_NEAR(f.summary(3 * 2 * dist.r_max()).mean_nu, f.box_nu(), kUniformFRelTol * f.box_nu());
}

TEST(DensityField, PredictionHoldsWhenTheBinsAreHalvedOrDoubled) {
  for (const Bed& b : kBedsUsed) {
    const ParticleSet s = read_bed(b);
    const DensityField f = field_of(s);
    const Recommendation r = recommend_for_field(f, ModelParams{s.d, 0.5, kK});
    const double at = r.model.T_over_N;
    for (double bins : {kFieldBinsPerWindow / 2, kFieldBinsPerWindow * 2}) {
      FieldOptions opt;
      opt.bins_per_window = bins;
      const double other = field_of(s, opt).evaluate(ModelParams{s.d, 0.5, kK}, r.sizes).model.T_over_N;
      EXPECT_NEAR(other, at, kResolutionRelTol * at) << b.file << " frame " << b.frame << " bins per window " << bins;
    }
  }
}

// Counted (machine-independent): on poured beds,
// settled and in progress, 2D and 3D, the recommended sizes measure within
// 5 % of the best of the scan and the field model predicts within 10 %.
TEST(DensityField, RecommendationOnPouredBedsIsNearTheBestOfTheScan) {
  for (const Bed& b : kBedsUsed) {
    const ParticleSet s = read_bed(b);
    const Packing p = to_packing(s, b.file);
    double best = measured(p, {2 * *std::max_element(s.radii.begin(), s.radii.end())});
    for (double nu : kScanNu) best = std::min(best, measured(p, recommend_cell_sizes(s.radii, ModelParams{s.d, nu, kK}).sizes));
    const Recommendation r = recommend_for_field(field_of(s), ModelParams{s.d, 0.5, kK});
    const double got = measured(p, r.sizes);
    EXPECT_LE(got, (1 + kBestOfScanRelTol) * best) << b.file << " frame " << b.frame;
    EXPECT_NEAR(r.model.T_over_N, got, kPredictionRelTol * got) << b.file << " frame " << b.frame;
    ASSERT_TRUE(r.field);
    if (!std::string(b.file).ends_with(".dump")) continue;
    // LAMMPS's beds stand in boxes far above them: there the box's nu alone
    // (the finding, kept as a check that the fixtures still show
    // it) predicts a half or more too little, and the field says so.
    EXPECT_TRUE(r.field->far_from_homogeneous()) << b.file << " frame " << b.frame;
    const Recommendation h = recommend_cell_sizes(s.radii, ModelParams{s.d, s.packing_fraction(), kK});
    EXPECT_LT(h.model.T_over_N, 0.6 * measured(p, h.sizes)) << b.file << " frame " << b.frame;
  }
}

// Counted: on beds the generator settles itself (placement bed: no LAMMPS
// or MercuryDPM needed), 2D and 3D, the same targets as on the poured ones;
// the box's nu alone predicts far too little there.
TEST(DensityField, RecommendationOnTheGeneratorsBedsIsNearTheBestOfTheScan) {
  struct BedSpec {
    int d;
    double omega;
    std::uint64_t seed;
  };
  for (const BedSpec& b : {BedSpec{3, 5, 1}, BedSpec{2, 10, 2}}) {
    PackingSpec sp;
    sp.d = b.d, sp.n = 2000, sp.nu = 0.15, sp.alpha = -3, sp.omega = b.omega, sp.seed = b.seed;
    sp.boundary = Boundary::walls, sp.placement = Placement::bed, sp.progress = false;
    const Packing p = generate_packing(sp);
    SCOPED_TRACE(::testing::Message() << "bed d " << b.d << " omega " << b.omega << " seed " << b.seed);
    const DensityField f(p.positions, p.radii, FieldBox{p.d, p.box, {false, false, false}});
    double best = measured(p, {2 * *std::max_element(p.radii.begin(), p.radii.end())});
    for (double nu : kScanNu) best = std::min(best, measured(p, recommend_cell_sizes(p.radii, ModelParams{p.d, nu, kK}).sizes));
    const Recommendation r = recommend_for_field(f, ModelParams{p.d, 0.5, kK});
    const double got = measured(p, r.sizes);
    EXPECT_LE(got, (1 + kBestOfScanRelTol) * best);
    EXPECT_NEAR(r.model.T_over_N, got, kPredictionRelTol * got);
    ASSERT_TRUE(r.field);
    EXPECT_TRUE(r.field->far_from_homogeneous());
    const Recommendation h = recommend_cell_sizes(p.radii, ModelParams{p.d, p.packing_fraction(), kK});
    EXPECT_LT(h.model.T_over_N, 0.8 * measured(p, h.sizes));
  }
}

TEST(DensityField, RecommendationOnHomogeneousPackingsIsNearTheBestOfTheScan) {
  constexpr std::uint64_t kSeed = 8;
  for (Boundary bc : {Boundary::periodic, Boundary::walls}) {
    const Scene<3> sc = random_scene<3>(8000, 0.3, -3, 8, bc, kSeed);
    const Packing p = packing_from(sc, bc);
    std::vector<double> x;
    for (const auto& q : sc.spheres)
      for (double c : q.x) x.push_back(c);
    const bool per = bc == Boundary::periodic;
    const DensityField f(x, p.radii, FieldBox{3, sc.box, {per, per, per}});
    double best = INFINITY;
    for (double nu : kScanNu) best = std::min(best, measured(p, recommend_cell_sizes(p.radii, ModelParams{3, nu, kK}).sizes));
    const Recommendation r = recommend_for_field(f, ModelParams{3, 0.3, kK});
    const double got = measured(p, r.sizes);
    EXPECT_LE(got, (1 + kBestOfScanRelTol) * best) << to_string(bc) << " seed " << kSeed;
    EXPECT_NEAR(r.model.T_over_N, got, kPredictionRelTol * got) << to_string(bc) << " seed " << kSeed;
    EXPECT_FALSE(r.field->far_from_homogeneous()) << to_string(bc);
  }
}

TEST(DensityField, RecommendCommandUsesTheFieldAndSaysSo) {
  const std::string bed = kBeds + "bed3d_o5_s1.dump";
  const Result text = hgrid_run("recommend " + bed, kNoCalibration);
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("far from homogeneous"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("local nu:"), std::string::npos) << text.out;
  const Result js = hgrid_run("recommend " + bed + " --json", kNoCalibration);
  ASSERT_EQ(js.status, 0) << js.err;
  const auto j = nlohmann::json::parse(js.out);
  EXPECT_EQ(j["nu_source"], "field");
  EXPECT_TRUE(j["field"]["far_from_homogeneous"].get<bool>());
  EXPECT_GT(j["field"]["mean_local_nu"].get<double>(), 3 * j["field"]["box_nu"].get<double>());
  // --homogeneous and --nu: the box's or the given nu, as before.
  const auto h = nlohmann::json::parse(hgrid_run("recommend " + bed + " --json --homogeneous", kNoCalibration).out);
  EXPECT_EQ(h["nu_source"], "box");
  EXPECT_TRUE(h["field"].is_null());
  const auto g = nlohmann::json::parse(hgrid_run("recommend " + bed + " --json --nu 0.4", kNoCalibration).out);
  EXPECT_EQ(g["nu_source"], "given");
  EXPECT_DOUBLE_EQ(g["nu"].get<double>(), 0.4);
  // count --cells optimal: the same sizes, and it says where they come from.
  const Result c = hgrid_run("count " + bed + " --cells optimal --model none --threads 1 --json", kNoCalibration);
  ASSERT_EQ(c.status, 0) << c.err;
  EXPECT_EQ(nlohmann::json::parse(c.out)["sizes"], j["sizes"]);
  EXPECT_NE(c.err.find("field model"), std::string::npos) << c.err;
}

// --boundary for a file that does not say its own (MercuryDPM's .data): the
// field of the walled bed, the sizes recommend_for_field gives it; a file
// that says another boundary, or a word not a boundary, is refused (exit 2).
TEST(DensityField, RecommendCommandTakesTheBoundaryAFileDoesNotSay) {
  const std::string bed = kBeds + "mdpm3d_o5_s1.data";
  const Result js = hgrid_run("recommend " + bed + " --frame 0 --boundary walls --K 0.2 --json", kNoCalibration);
  ASSERT_EQ(js.status, 0) << js.err;
  const auto j = nlohmann::json::parse(js.out);
  EXPECT_EQ(j["boundary"], "walls");
  const ParticleSet s = read_bed(Bed{"mdpm3d_o5_s1.data", 0});
  const Recommendation r = recommend_for_field(field_of(s), ModelParams{3, 0.5, kK});
  EXPECT_EQ(j["sizes"].get<std::vector<double>>(), r.sizes);
  EXPECT_DOUBLE_EQ(j["field"]["mean_local_nu"].get<double>(), r.field->summary.mean_nu);
  const auto assumed = nlohmann::json::parse(hgrid_run("recommend " + bed + " --frame 0 --K 0.2 --json", kNoCalibration).out);
  EXPECT_NE(assumed["field"]["mean_local_nu"].get<double>(), r.field->summary.mean_nu);  // periodic, assumed
  const Result says = hgrid_run("recommend " + kBeds + "bed3d_o5_s1.dump --boundary periodic", kNoCalibration);
  EXPECT_EQ(says.status, 2);
  EXPECT_NE(says.err.find("boundary"), std::string::npos) << says.err;
  const Result bad = hgrid_run("recommend " + bed + " --boundary sideways", kNoCalibration);
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("boundary"), std::string::npos) << bad.err;
}

// A run over several snapshots: the cost per particle over all of them,
// each snapshot weighed by its particles (exactly the single snapshots'
// costs averaged), within the target of what the grid counts over them.
TEST(DensityField, SnapshotsOfARunAreAveragedPerParticle) {
  const std::string bed = kBeds + "bed3d_o5_s1.dump";
  const ParticleSet a = read_particles(bed, Isolation::none, 0), b = read_particles(bed, Isolation::none, 1);
  DensityField both = field_of(a);
  both.add_frame(b.positions, b.radii, FieldBox{b.d, *b.box, b.periodic_per_axis()});
  EXPECT_EQ(both.frames(), 2u);
  EXPECT_EQ(both.size(), a.size() + b.size());
  const std::vector<double> sizes = recommend_for_field(both, ModelParams{3, 0.5, kK}).sizes;
  const ModelParams mp{3, 0.5, kK};
  const double na = double(a.size()), nb = double(b.size());
  const double ta = field_of(a).evaluate(mp, sizes).model.T_over_N, tb = field_of(b).evaluate(mp, sizes).model.T_over_N;
  const double predicted = both.evaluate(mp, sizes).model.T_over_N;
  EXPECT_NEAR(predicted, (na * ta + nb * tb) / (na + nb), 1e-12 * predicted);
  const double counted = (na * measured(to_packing(a, bed), sizes) + nb * measured(to_packing(b, bed), sizes)) / (na + nb);
  EXPECT_NEAR(predicted, counted, kPredictionRelTol * counted);
  // The command: --frames 0:1 gives these sizes; bad ranges name the field.
  const Result r = hgrid_run("recommend " + bed + " --frames 0:1 --json", kNoCalibration);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["frames"], nlohmann::json({0, 1}));
  EXPECT_EQ(j["n"].get<std::size_t>(), a.size() + b.size());
  EXPECT_EQ(j["sizes"].get<std::vector<double>>(), sizes);
  for (const char* bad : {"1:0", "0:5", "0-1", "x:1"}) {
    const Result e = hgrid_run("recommend " + bed + " --frames " + bad, kNoCalibration);
    EXPECT_EQ(e.status, 2) << bad;
    EXPECT_EQ(e.err.rfind("hgrid: error: frames:", 0), 0u) << e.err;
    EXPECT_TRUE(e.out.empty()) << bad;
  }
}

// A pour as LAMMPS's examples/pour sets it up, `boundary p p fm`: the field
// takes x and y periodic (windows wrap there), z walled.
using DensityFieldFiles = TempDir;

TEST_F(DensityFieldFiles, MixedBoundaryDumpIsPeriodicWhereTheFileSays) {
  std::ifstream in(kBeds + "bed3d_o5_s1.dump");
  std::stringstream text;
  text << in.rdbuf();
  std::string dump = text.str();
  for (std::size_t at = 0; (at = dump.find("BOX BOUNDS ff ff fm", at)) != std::string::npos;)
    dump.replace(at, 19, "BOX BOUNDS pp pp fm");
  const std::string file = path("pour.dump");
  std::ofstream(file) << dump;
  const ParticleSet s = read_particles(file);
  ASSERT_TRUE(s.mixed_boundary);
  const std::array<bool, 3> per = s.periodic_per_axis();
  EXPECT_TRUE(per[0] && per[1] && !per[2]);
  const Result r = hgrid_run("recommend " + file + " --json", kNoCalibration);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["nu_source"], "field");
  EXPECT_TRUE(j["field"]["far_from_homogeneous"].get<bool>());
  // Wrapping x and y adds the neighbours across the side walls the walled
  // file lacks: the periodic field holds more than the walled one.
  const ParticleSet w = read_particles(kBeds + "bed3d_o5_s1.dump");
  const ModelParams mp{3, 0.5, kK};
  const std::vector<double> sizes = j["sizes"].get<std::vector<double>>();
  EXPECT_GT(field_of(s).evaluate(mp, sizes).model.T_cd_over_N, field_of(w).evaluate(mp, sizes).model.T_cd_over_N);
}

// A homogeneous packing keeps the paper's sizes at the box's nu (the
// figures' packings: their counts and model columns do not move).
TEST(DensityField, HomogeneousFileKeepsTheBoxSizes) {
  constexpr std::uint64_t kSeed = 12;
  const Packing p = packing_from(random_scene<3>(3000, 0.4, -3, 10, Boundary::periodic, kSeed), Boundary::periodic);
  const Recommendation r = recommend_for_packing(p, kK);
  ASSERT_TRUE(r.field);
  EXPECT_FALSE(r.field->sizes_from_field());
  EXPECT_EQ(r.sizes, recommend_cell_sizes(p.radii, ModelParams{3, p.packing_fraction(), kK}).sizes);
  EXPECT_EQ(r.sizes, r.field->homogeneous_sizes);
}

}  // namespace
}  // namespace hgrid::test
