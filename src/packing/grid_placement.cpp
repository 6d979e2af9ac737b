#include "hgridlab/packing/grid_placement.hpp"

#include "hgridlab/grid/dispatch.hpp"
#include "hgridlab/grid/hgrid.hpp"

namespace hgrid {

GridPlacement place_in_grid(const Packing& p, const GridParams& params) {
  return dispatch(p.d, p.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    const auto spheres = p.spheres<D>();
    const HGrid<D, decltype(bnd)::value> grid(spheres, p.extent<D>(), params);
    GridPlacement g;
    g.sizes = grid.sizes();
    g.level.reserve(spheres.size());
    g.cell.reserve(spheres.size());
    for (const auto& s : spheres) {
      const auto at = grid.placement(s);
      g.level.push_back(at.level + 1);
      g.cell.push_back(at.cell);
    }
    return g;
  });
}

}  // namespace hgrid
