// Choosing the HGrid cell sizes for a size distribution (docs/MODEL.md section 4;
// paper Sect. 5): linear, exponential, constant ratio of particles per cell,
// optimal; and the best number of levels L* for each.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/model.hpp"

namespace hgrid {

enum class CellMethod { linear, exponential, constant, optimal };

/// "linear" | "exponential" | "constant" | "optimal"; anything else throws
/// InputError naming `field`.
CellMethod parse_cell_method(const std::string& name, const std::string& field = "cells");
const char* to_string(CellMethod m);

struct SizeChoice {
  int levels = 0;
  std::vector<double> sizes;  // s_1..s_L, absolute (the distribution's unit)
  ModelResult model;
};

/// The smallest K for which L* is searched: below it cell accesses are so
/// cheap that the best L runs away (K = 0: more levels always pay).
inline constexpr double kMinSearchK = 1e-3;

/// Relative tolerance that defines L* for the optimal method: the smallest L
/// whose optimum is within this of the best over all L (extra levels collapse).
inline constexpr double kLevelsFlatRelTol = 1e-6;

/// Sizes s_1..s_L by one method for a fixed L >= 1 (q: ratio m_{h+1}/m_h of
/// the constant method, > 0). Optimal minimises T over s_1..s_{L-1} under
/// s_0 = 2 r_min <= s_1 <= ... <= s_L = 2 r_max.
std::vector<double> cell_sizes(const Distribution& dist, const ModelParams& p, CellMethod method,
                               int levels, double q = 1.0);

/// Sizes and cost for `levels`, or, without it, for the best L (L*): the L
/// with the least T (ties and, for optimal, anything within kLevelsFlatRelTol
/// go to the smallest L). The scan stops at kMaxLevels levels (constant and
/// optimal methods: 256); a best L at that limit, or K < kMinSearchK, throws
/// InputError("K").
SizeChoice choose_cell_sizes(const Distribution& dist, const ModelParams& p, CellMethod method,
                             std::optional<int> levels = std::nullopt, double q = 1.0);

/// Model sizes made ready for GridParams: levels the optimum collapsed onto
/// each other merged (strictly increasing), and the last size at least
/// `largest_diameter` despite rounding.
std::vector<double> sizes_for_grid(std::vector<double> sizes, double largest_diameter);

/// T/N for every L = 1..max_levels by one method (the curves of Figs. 6 and 9).
std::vector<double> cost_versus_levels(const Distribution& dist, const ModelParams& p,
                                       CellMethod method, int max_levels, double q = 1.0);

}  // namespace hgrid
