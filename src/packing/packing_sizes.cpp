#include "packing/packing_sizes.hpp"

#include <algorithm>

#include "model/cell_sizes.hpp"
#include "model/distribution.hpp"
#include "grid/error.hpp"

namespace hgrid {

std::vector<double> model_sizes(const Packing& p, const SizeRequest& r, Search search, double K) {
  if (p.size() == 0) throw InputError("cells", "the packing has no particles to fit sizes to");
  const Empirical dist(p.radii);
  const ModelParams mp{p.d, p.packing_fraction(), K, search};
  std::vector<double> s = choose_cell_sizes(dist, mp, r.method, r.levels, r.q).sizes;
  // The optimum may collapse levels onto each other: keep strictly increasing
  // sizes, and make the last one hold the largest particle despite rounding.
  s.erase(std::unique(s.begin(), s.end(), [](double a, double b) { return !(b > a); }), s.end());
  const double d_max = 2 * *std::max_element(p.radii.begin(), p.radii.end());
  s.back() = std::max(s.back(), d_max);
  return s;
}

}  // namespace hgrid
