// Cell sizes for one's own particles: the cost model's optimal Top-Down (or
// Bottom-Up) grid for a list of radii, in the radii's own unit, with the
// predicted cost and the predicted speed-up over the single-level linked cell.
#pragma once
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hgridlab/calibration/k_choice.hpp"
#include "hgridlab/io/particle_file.hpp"
#include "hgridlab/model/density_field.hpp"
#include "hgridlab/model/model.hpp"
#include "hgridlab/model/time_model.hpp"
#include "hgridlab/packing/packing.hpp"

namespace hgrid {

/// With a machine's time model (docs/MODEL.md section 9): its coefficients
/// for the recommendation's dimension and the number of particles.
struct TimeModelUse {
  TimeCoefficients coef;
  double n = 0;
  double box_volume = 0;  // > 0: the particles fill part of a larger box (expected_time_terms)
};

/// What a recommendation from positions used (recommend_for_field): the
/// packing's density field and, beside the field's prediction (in
/// Recommendation::model), the homogeneous model's at the box's nu.
struct FieldUse {
  FieldSummary summary;        // local nu in windows of the linked cell's scan, 3 x 2 r_max
  double nu_effective = 0;     // the homogeneous nu with the field's count at the chosen sizes
  double homogeneous_T_over_N = 0;  // the paper's model at the box's nu, at the chosen sizes
  std::vector<double> homogeneous_sizes;  // what the box's nu alone recommends
  bool sizes_from_field() const { return far_from_homogeneous(); }
  double homogeneous_sizes_T_over_N = 0;  // the field model's T/N for them
  /// The box is far from homogeneous: the box's nu misses the particles'
  /// mean local nu by more than kFarFromHomogeneous of it.
  bool far_from_homogeneous() const {
    return std::abs(summary.mean_nu - summary.box_nu) > kFarFromHomogeneous * summary.mean_nu;
  }
  static constexpr double kFarFromHomogeneous = 0.25;
};

struct Recommendation {
  std::vector<double> sizes;  // cell sizes s_1..s_L, ready for GridParams (radii's unit)
  ModelResult model;          // the cost model at `sizes`
  double linked_cell_size = 0;  // 2 r_max: the one level of the linked cell
  ModelResult linked_cell;      // the cost model for it
  double r_min = 0, r_max = 0;
  int levels() const { return static_cast<int>(sizes.size()); }
  /// Predicted T/N of the linked cell over that of `sizes`.
  double speedup() const { return linked_cell.T_over_N / model.T_over_N; }
  /// With a time model: the sizes minimise its predicted seconds of one
  /// build + query, and these are its predictions for them and the linked cell.
  std::optional<PredictedSeconds> seconds, linked_cell_seconds;
  double speedup_seconds() const { return seconds ? linked_cell_seconds->total() / seconds->total() : 0; }
  /// LAMMPS `neighbor multi` collection bounds (diameters, radii's unit)
  /// from its own cost model (model/lammps_multi.hpp), for a cubic periodic
  /// box of the particles at nu; where its coefficients came from. Filled by
  /// add_lammps_collections (callers that want only the sizes skip its search).
  std::vector<double> lammps_collections;
  std::string lammps_model_source;
  /// Set by recommend_for_field: the field it used.
  std::optional<FieldUse> field;
  /// Set by recommend_tilted: c, the tilted box's inflation (1: untilted).
  double tilt_inflation = 1;
};

/// The optimal sizes (best number of levels L*, or with `time` the
/// time-optimal sizes, time_optimal_sizes) for the empirical
/// distribution of `radii` (> 0, finite; any unit) and p (d, nu, K, search).
/// Computed in units of r_min and scaled back, so that the same radii in
/// another unit give the same sizes in that unit. Throws InputError.
Recommendation recommend_cell_sizes(const std::vector<double>& radii, const ModelParams& p,
                                    const std::optional<TimeModelUse>& time = std::nullopt);

/// The sizes for particles whose positions are known (docs/MODEL.md section
/// 14). Far from homogeneous (FieldUse::far_from_homogeneous): among the
/// homogeneous model's optima for nu = 0.05, 0.1, ..., 0.75 and for the
/// field's effective nu (found by iterating nu -> sizes -> the field's
/// effective nu for them), the ones with the least field-model T/N (with
/// `time`: the least predicted seconds at each one's effective nu). Close to
/// homogeneous: the paper's optimum at the box's nu (recommend_cell_sizes).
/// Either way the model in the result is the field model's; p.nu is not used.
Recommendation recommend_for_field(const DensityField& field, const ModelParams& p,
                                   std::optional<TimeModelUse> time = std::nullopt);

/// A tilted (sheared, triclinic) box's sizes (docs/MODEL.md section 12):
/// its grid searches the mapped packing, radii and cell sizes c times larger
/// (c = TiltedBox::inflation() >= 1) with random centres at packing fraction
/// c^d nu (above 1 for a dense sheared packing). The mapped packing's
/// optimum at p (p.nu the box's), its sizes and the linked cell's divided by
/// c; the model's T/N is the mapped packing's, what the tilted grid counts.
/// c = 1 is recommend_cell_sizes. InputError for c < 1 or not finite.
Recommendation recommend_tilted(const std::vector<double>& radii, const ModelParams& p, double inflation,
                                const std::optional<TimeModelUse>& time = std::nullopt);

/// c of a d-dimensional box with side lengths `length` (its first d) and
/// tilts xy, xz, yz (2D: xy only): TiltedBox::inflation, 1 untilted.
double tilt_inflation(int d, std::span<const double> length, const std::array<double, 3>& tilt);
/// The same for a file's box (1 for none).
double tilt_inflation(const ParticleSet& s);

/// The density field of a file's particles (positions in an untilted box),
/// or nothing when the file has no positions or box, or a tilted box.
std::optional<DensityField> density_field_of(const ParticleSet& s);
/// The same for a packing (nothing for a tilted one).
std::optional<DensityField> density_field_of(const Packing& p);

/// What `hgrid recommend` gives a packing (no time model): the field model
/// when it has positions in an untilted box, else the box's nu; with LAMMPS
/// collections for the nu used (the field's effective one).
Recommendation recommend_for_packing(const Packing& p, double K, Search search = Search::top_down);

/// Fills r.lammps_collections and r.lammps_model_source with
/// lammps_collections_for(radii, d, nu).
void add_lammps_collections(Recommendation& r, const std::vector<double>& radii, int d, double nu);

/// LAMMPS collection bounds for `radii` at packing fraction nu in d
/// dimensions (a cubic periodic box), with lammps_coefficients(source).
std::vector<double> lammps_collections_for(const std::vector<double>& radii, int d, double nu,
                                           std::string* source = nullptr);

/// The time model a recommendation uses for `cost` ("count": none; "time":
/// the stored calibration's for dimension d, an InputError naming `cost` if
/// there is none; "auto": the stored one when K came from the calibration
/// and it has a time model for d), for n particles.
std::optional<TimeModelUse> choose_time_model(const std::string& cost, const KChoice& k, int d, double n);

}  // namespace hgrid
