// Optimal cell sizes for a power law through hgridlab::hgridlab, and the
// measurement record of the grid at those sizes.
#include <cstdio>

#include <hgridlab/hgridlab.hpp>  // the umbrella: every public header

int main() {
  using namespace hgrid;
  const PowerLaw dist(-3.0, 10.0);
  const SizeChoice c = choose_cell_sizes(dist, ModelParams{}, CellMethod::optimal);
  std::printf("L* = %d, T/N = %.4f\n", c.levels, c.model.T_over_N);
  PackingSpec spec;
  spec.n = 2000, spec.nu = 0.3, spec.alpha = -3.0, spec.omega = 10.0, spec.seed = 1;
  const Packing p = generate_packing(spec);
  MeasureOptions o;
  o.model = true;
  const Measurement m = measure(p, GridParams{.sizes = model_sizes(p, SizeRequest{}, Search::top_down, 0.2)}, o);
  std::printf("measured T/N = %.4f, model %.4f (%llu contacts)\n", m.T_over_N, m.model_T_over_N,
              (unsigned long long)m.counts.contacts);
  return c.levels >= 1 && c.model.T_over_N > 0 && m.n == 2000 && m.T_over_N > 0 ? 0 : 1;
}
