// Fitting the LAMMPS multi cost model (model/lammps_multi.hpp) to measured
// neighbour-list builds: non-negative least squares on relative residuals,
// as the time model is fitted (docs/MODEL.md sections 9 and 11).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "hgridlab/model/lammps_multi.hpp"

namespace hgrid {

/// One measured build: the model's terms for its packing and bounds, and the
/// seconds LAMMPS took per build. `packing` numbers the training packings:
/// what a build costs whatever the bounds (binning, ghosts, storing the
/// pairs found) is one free constant per packing, not a shared coefficient.
struct LammpsSample {
  LammpsTerms terms;
  double seconds = 0;
  int packing = 0;
};

struct LammpsFit {
  LammpsCoefficients coef;  // `particles`: the packings' constants over their N, averaged
  std::array<double, kLammpsTerms> stderr_{};  // standard errors of coef
  double rms_rel = 0, max_rel = 0;             // |predicted / measured - 1| over the samples
};

/// Needs more samples than unknowns; throws InputError otherwise.
LammpsFit fit_lammps(const std::vector<LammpsSample>& samples);

/// The coefficients `hgrid recommend` uses: those of the fit.json that
/// $HGRID_LAMMPS_MODEL names (written by bench/lammps_model for one's own
/// LAMMPS build), else default_lammps_coefficients(). `source` tells which.
LammpsCoefficients lammps_coefficients(std::string* source = nullptr);

}  // namespace hgrid
