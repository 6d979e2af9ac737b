// `hgrid model`'s question and answer: the cost model for one size
// distribution (paper Sects. 3-5), its cell sizes by a method, and what
// replaces or refines them (this machine's time model, the excluded-volume
// model). The tool parses, calls answer_model, prints.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "hgridlab/calibration/calibration.hpp"
#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/model.hpp"
#include "hgridlab/model/time_model.hpp"

namespace hgrid {

struct ModelQuestion {
  ModelParams params;                      // d, nu, K, search
  CellMethod cells = CellMethod::optimal;
  std::optional<int> levels;               // none: the best L*
  double q = 1.0;                          // constant method: m_{h+1} / m_h
  bool excluded = false;                   // hard spheres: the excluded-volume model for the sizes
  bool excluded_sizes = false;             // with excluded: refine the sizes under it
  CostKind cost = CostKind::count;         // time: this machine's time optimum replaces the count one
  double n = 1e6;                          // particles, for cost = time
};

struct ModelAnswer {
  int levels = 0;
  std::vector<double> sizes;               // in units of r_min
  ModelResult model;                       // the model reported (excluded-volume when asked)
  ModelResult random;                      // the paper's model (random centres) for the paper's sizes
  std::optional<PredictedSeconds> seconds;  // cost = time: the predicted build + query
  double T_over_N_excluded_paper_sizes = 0;  // excluded_sizes: before the refinement
  int excluded_size_evaluations = 0;
};

/// Validates the question (InputError naming the field) and answers it; the
/// time model comes from the stored calibration (calibrated_time_model).
ModelAnswer answer_model(const Distribution& dist, const ModelQuestion& q);

/// The answer as a JSON object (`hgrid model --json` without its "params",
/// which echo the command's options): levels, sizes, T/N and its parts,
/// the random-centre T/N beside an excluded-volume one, the predicted
/// seconds for cost = time, the refinement's before and evaluations, and the
/// per-level T_cd, P and m.
std::string model_answer_json(const ModelAnswer& a, const ModelQuestion& q);
/// The answer as text: L, T/N and its parts, what else was asked, and a
/// row per level.
std::string model_answer_text(const ModelAnswer& a, const ModelQuestion& q);

}  // namespace hgrid
