// Internals of cell_sizes.cpp: the constant-ratio shooting and the optimiser.
#pragma once
#include <vector>

#include "hgridlab/model/detail/model_cost.hpp"

namespace hgrid::detail {

/// Eq. (37)-(38): interior sizes with m_{h+1} = q m_h, s_0 and s_L fixed,
/// found by shooting on s_1 (monotone, bracketed; works for step CDFs).
std::vector<double> constant_ratio_sizes(const CostModel& cm, int L, double q);

/// Minimise T over s_1..s_{L-1} from each start (each of length L, ending
/// in s_L); returns the best sizes found. Damped Newton on ln s_k with the
/// analytic gradient (model_optimize.cpp), plus a derivative-free coordinate
/// polish for step CDFs.
std::vector<double> optimise_sizes(const CostModel& cm, int L,
                                   const std::vector<std::vector<double>>& starts);

}  // namespace hgrid::detail
