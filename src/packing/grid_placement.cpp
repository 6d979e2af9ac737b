#include "hgridlab/packing/grid_placement.hpp"

#include "hgridlab/grid/dispatch.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/grid/tilted.hpp"

namespace hgrid {

GridPlacement place_in_grid(const Packing& p, const GridParams& params) {
  return dispatch(p.d, p.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    const auto spheres = p.spheres<D>();
    GridPlacement g;
    const auto place = [&](const auto& grid, const auto& to_grid) {
      g.level.reserve(spheres.size());
      g.cell.reserve(spheres.size());
      for (const auto& s : spheres) {
        const auto at = grid.placement(to_grid(s));
        g.level.push_back(at.level + 1);
        g.cell.push_back(at.cell);
      }
    };
    if (p.tilted()) {  // the cells of the mapped grid (grid/tilted.hpp)
      const TiltedBox<D> box = p.tilted_box<D>();
      const TiltedHGrid<D> grid(spheres, box, params);
      g.sizes = grid.sizes();
      const double c = grid.inflation();
      place(grid.mapped_grid(), [&](const Sphere<D>& s) { return Sphere<D>{box.mapped(s.x), c * s.r}; });
    } else {
      const HGrid<D, decltype(bnd)::value> grid(spheres, p.extent<D>(), params);
      g.sizes = grid.sizes();
      place(grid, [](const Sphere<D>& s) { return s; });
    }
    return g;
  });
}

}  // namespace hgrid
