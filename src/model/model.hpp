// The analytic cost model of the HGrid (docs/MODEL.md section 3; paper Sect. 3).
#pragma once
#include <vector>

#include "hgridlab/model/distribution.hpp"
#include "hgridlab/grid/params.hpp"

namespace hgrid {

struct ModelParams {
  int d = 3;          // dimension, 2 or 3
  double nu = 0.7;    // packing fraction, in (0, 1] (unless overfull)
  double K = 0.2;     // cell-access time / overlap-test time, >= 0
  Search search = Search::top_down;
  /// Random centres whose spheres fill more than the box (nu > 1 allowed):
  /// the model of a tilted box's grid, which searches its spheres enlarged
  /// (docs/MODEL.md section 12). Never set from a user's input.
  bool overfull = false;
};

/// Throws InputError naming the field for d not in {2,3}, nu not in (0, 1]
/// (any nu > 0 when overfull), K < 0, NaN.
void validate(const ModelParams& p);

/// Everything per particle (divided by N). Per-level vectors have L entries.
struct ModelResult {
  double T_over_N = 0, T_cd_over_N = 0, T_ca_over_N = 0;  // Eq. (27): T = T_cd + K T_ca
  std::vector<double> sizes;  // s_1..s_L, absolute
  std::vector<double> P;      // fraction of particles at level h, P_h
  std::vector<double> m;      // particles per cell, m_h (Eq. 11)
  std::vector<double> T_cd;   // narrow-phase checks of level-h particles / N
  std::vector<double> T_ca;   // cell accesses of level-h particles / N
  std::vector<double> T_cd_pair;  // L x L, [h * L + j]: checks of level-h particles in level j / N
  int levels() const { return static_cast<int>(sizes.size()); }
};

/// T/N and its parts for cell sizes s_1..s_L (same length unit as the radii;
/// non-decreasing, finite, > 0, s_L >= 2 r_max). Level h owns the radii in
/// (s_{h-1}/2, s_h/2] with s_0 = 2 r_min (docs/MODEL.md section 1).
ModelResult evaluate_model(const Distribution& dist, const ModelParams& p,
                           const std::vector<double>& sizes);

/// Mean number of level-j cells scanned by a level-h particle, b(j,h)
/// (Eq. 16; levels 1-based). Returns 0 when level h holds no particles.
double cross_level_cells(const Distribution& dist, int d, const std::vector<double>& sizes,
                         int j, int h);

}  // namespace hgrid
