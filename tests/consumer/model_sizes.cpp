// Optimal cell sizes for a power law through hgridlab::hgridlab.
#include <cstdio>

#include "model/cell_sizes.hpp"
#include "model/distribution.hpp"

int main() {
  using namespace hgrid;
  const PowerLaw dist(-3.0, 10.0);
  const SizeChoice c = choose_cell_sizes(dist, ModelParams{}, CellMethod::optimal);
  std::printf("L* = %d, T/N = %.4f\n", c.levels, c.model.T_over_N);
  return c.levels >= 1 && c.model.T_over_N > 0 ? 0 : 1;
}
