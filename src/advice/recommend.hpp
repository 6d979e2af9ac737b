// Cell sizes for one's own particles: the cost model's optimal Top-Down (or
// Bottom-Up) grid for a list of radii, in the radii's own unit, with the
// predicted cost and the predicted speed-up over the single-level linked cell.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "hgridlab/calibration/k_choice.hpp"
#include "hgridlab/model/model.hpp"
#include "hgridlab/model/time_model.hpp"

namespace hgrid {

/// With a machine's time model (docs/MODEL.md section 9): its coefficients
/// for the recommendation's dimension and the number of particles.
struct TimeModelUse {
  TimeCoefficients coef;
  double n = 0;
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
};

/// The optimal sizes (best number of levels L*, or with `time` the
/// time-optimal sizes, time_optimal_sizes) for the empirical
/// distribution of `radii` (> 0, finite; any unit) and p (d, nu, K, search).
/// Computed in units of r_min and scaled back, so that the same radii in
/// another unit give the same sizes in that unit. Throws InputError.
Recommendation recommend_cell_sizes(const std::vector<double>& radii, const ModelParams& p,
                                    const std::optional<TimeModelUse>& time = std::nullopt);

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
