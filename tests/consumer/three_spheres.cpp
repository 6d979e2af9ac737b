// Counts the overlapping pairs of three spheres through hgridlab::core.
#include <array>
#include <cstdio>
#include <vector>

#include <hgridlab/grid/hgrid.hpp>
#include <hgridlab/grid/version.hpp>

int main() {
  using namespace hgrid;
  const std::vector<Sphere<3>> spheres{{{1.0, 1.0, 1.0}, 0.5}, {{1.8, 1.0, 1.0}, 0.5}, {{5.0, 5.0, 5.0}, 1.0}};
  const HGrid<3, Boundary::periodic> grid(spheres, Extent<3>{10, 10, 10}, GridParams{.sizes = {1.0, 2.0}});
  int pairs = 0;
  grid.for_each_pair([&](std::uint32_t, std::uint32_t) { ++pairs; });
  std::printf("hgridlab %s: %d pair(s)\n", HGRIDLAB_VERSION, pairs);
  return pairs == 1 ? 0 : 1;
}
