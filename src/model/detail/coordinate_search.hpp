// The coordinate search both time-based size choices use (time_model.cpp,
// lammps_multi.cpp): each bound but the last is multiplied or divided by a
// step while that lowers the cost, for each step in turn.
#pragma once
#include <span>
#include <vector>

namespace hgrid::detail {

/// Improves s (increasing; s.back() fixed) in place; `cost` is its value on
/// entry and on return. No bound goes below `bottom`.
template <class Cost>
void coordinate_search(std::vector<double>& s, double& cost, double bottom, std::span<const double> steps,
                       Cost&& cost_of) {
  const int L = static_cast<int>(s.size());
  for (const double step : steps)
    for (bool improved = true; improved;) {
      improved = false;
      for (int h = 0; h + 1 < L; ++h)
        for (const double f : {1.0 / step, step}) {
          std::vector<double> trial = s;
          trial[h] *= f;
          if (trial[h] < bottom || (h > 0 && !(trial[h] > trial[h - 1])) || !(trial[h] < trial[h + 1])) continue;
          const double v = cost_of(trial);
          if (v < cost) s = std::move(trial), cost = v, improved = true;
        }
    }
}

}  // namespace hgrid::detail
