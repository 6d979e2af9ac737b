// The cost model over a packing's own density field (docs/MODEL.md section 14;
// beyond the paper, whose model assumes centres spread evenly over the box).
//
// A poured bed fills the bottom of its box, a pour in progress is a gas over
// a bed: the box's packing fraction says little about what a particle's
// search meets. The paper's narrow-phase count is a sum over particles of
// what each one's scanned cells hold: a level-h particle of radius r scans,
// on level j, cells covering on average a cube of side 2 s_j + 2 r centred on
// it (Eq. 16), the own level 27 (3D) or 9 (2D) cells of side s_h counted
// once per pair. The field model keeps the model's terms and replaces, in
// each level pair's count, the random centres' density n_j = N_j / V by the
// density of level-j centres actually found in that window around each
// level-h particle (itself left out), averaged over the level-h particles:
//   T_cd = sum_{h,j} T_cd(h,j) F(h,j),
//   F(h,j) = sum_{i in h} c_j(i) / sum_{i in h} n_j w_{ij}^d,
// with c_j(i) the level-j centres in particle i's window of side w_{ij}.
// The windows are the model's own scan extents, so the field has no free
// resolution; the centres are binned on a grid whose bins are an eighth of
// the smallest window (the rule, kFieldBinsPerWindow), and windows are summed
// from its cumulative table with each bin's centres spread evenly over it.
// Windows cross periodic axes; on walled axes they reach past the wall,
// where no centre lies, as the grid's scans stop there. F = 1 for centres
// spread evenly over a periodic box; the cell accesses (K T_ca) are the
// model's.
#pragma once
#include <array>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/model.hpp"

namespace hgrid {

/// Bins of the field's grid per side of the smallest window (the rule; the
/// prediction moves by well under 1 % when it is halved or doubled:
/// tests/test_density_field.cpp).
inline constexpr double kFieldBinsPerWindow = 8;
/// The most bins of the field's grid; beyond it the bins grow (a dilute box).
inline constexpr std::size_t kFieldMaxBins = std::size_t(1) << 22;
/// The most particles whose windows are summed (every k-th, in file order).
inline constexpr std::size_t kFieldMaxSamples = std::size_t(1) << 15;

/// A box [0, side_k) per axis, periodic or walled per axis.
struct FieldBox {
  int d = 3;
  std::array<double, 3> side{};
  std::array<bool, 3> periodic{};
};

/// Discretisation of the field (defaults: the rule above).
struct FieldOptions {
  double bins_per_window = kFieldBinsPerWindow;
  std::size_t max_bins = kFieldMaxBins;
  std::size_t max_samples = kFieldMaxSamples;
};

/// Where the particles are, at the resolution of one window side `window`:
/// each sampled particle's local packing fraction (the spheres whose centres
/// lie in the cube of side `window` centred on it, itself left out, over the
/// cube's volume inside walled axes: the particles' own density), and the fraction of the box's window-sized cells that
/// hold no centre.
struct FieldSummary {
  double window = 0;
  double box_nu = 0;         // the particles' volume over the box's
  double mean_nu = 0;        // the local nu averaged over the particles
  double empty_fraction = 0; // cells of side `window` holding no centre
  std::vector<double> histogram;  // fraction of particles per local-nu bin [0, 0.05), [0.05, 0.1), ...
  static constexpr double kHistogramBin = 0.05;
};

/// The field model's cost for one set of sizes.
struct FieldResult {
  ModelResult model;        // as evaluate_model's, its pair counts (T_cd_pair) rescaled by F
  double effective_nu = 0;  // the homogeneous nu with the same narrow-phase count: box nu x (T_cd / the box's T_cd)
};

/// A packing's positions and radii with its box, for the field model; or
/// several snapshots of a run (add_frame), whose costs are averaged per
/// particle (sizes are set once per run).
/// positions: N x d, inside the box (wrapped on periodic axes); radii > 0.
class DensityField {
 public:
  DensityField(std::span<const double> positions, std::span<const double> radii, const FieldBox& box,
               const FieldOptions& opt = {});
  /// Another snapshot (the same d; its own particles and box).
  void add_frame(std::span<const double> positions, std::span<const double> radii, const FieldBox& box);

  int d() const { return frames_.front().box.d; }
  std::size_t frames() const { return frames_.size(); }
  /// Particles over all snapshots.
  std::size_t size() const { return radii_.size(); }
  const FieldBox& box(std::size_t frame = 0) const { return frames_.at(frame).box; }
  /// The particles' volume over the box's (over all snapshots).
  double box_nu() const;
  /// The box's volume (area in 2D), averaged over the snapshots.
  double volume() const;
  /// The radii of every snapshot (the distribution sizes are chosen for).
  const std::vector<double>& radii() const { return radii_; }

  /// The field model for `sizes` (p.nu is ignored: each snapshot's model
  /// terms are taken at its box's nu, and F rescales them), per particle
  /// over all snapshots.
  FieldResult evaluate(const ModelParams& p, const std::vector<double>& sizes) const;
  /// F(h,j) of the last formula above for one snapshot, L x L ([h * L + j],
  /// 0 where the model has no such pair).
  std::vector<double> factors(const ModelParams& p, const std::vector<double>& sizes, std::size_t frame = 0) const;

  /// The summary at one window side (e.g. the linked cell's scan, 3 x 2 r_max),
  /// over all snapshots.
  FieldSummary summary(double window) const;

 private:
  struct Frame {
    FieldBox box;
    std::vector<double> pos, radii;
    std::vector<std::size_t> samples;
    double spheres = 0, volume = 0;
    std::shared_ptr<const Empirical> dist;  // its radii, sorted once
  };
  Frame make_frame(std::span<const double> positions, std::span<const double> radii, const FieldBox& box) const;
  ModelResult frame_model(const Frame& f, const ModelParams& p, const std::vector<double>& sizes) const;
  std::vector<double> frame_factors(const Frame& f, const ModelResult& base, const std::vector<double>& sizes) const;

  FieldOptions opt_;
  std::vector<Frame> frames_;
  std::vector<double> radii_;
  std::shared_ptr<const Empirical> all_;  // every snapshot's radii, sorted once
};

}  // namespace hgrid
