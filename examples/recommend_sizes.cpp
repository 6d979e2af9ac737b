// Cell sizes for your own particles: the cost model evaluated where they
// are (their density field; docs/MODEL.md section 14), then the grid built
// with those sizes, its prediction against what it counts. Any particle file
// (docs/PARTICLE_FILES.md). Needs the full library, hgridlab::hgridlab.
//   build-examples/recommend_sizes tests/data/beds/bed3d_o5_s1.dump
#include <cstdio>

#include <hgridlab/hgridlab.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s PARTICLE_FILE\n", argv[0]);
    return 2;
  }
  using namespace hgrid;
  try {
    const Packing p = to_packing(read_particles(argv[1]), argv[1]);
    const Recommendation r = recommend_for_packing(p, /*K=*/0.2);  // the paper's K
    std::printf("%d levels, cell sizes:", r.levels());
    for (double s : r.sizes) std::printf(" %g", s);
    if (r.field)
      std::printf("\nlocal nu %.3g around the particles, %.3g over the box%s", r.field->summary.mean_nu,
                  r.field->summary.box_nu, r.field->far_from_homogeneous() ? " (far from homogeneous)" : "");
    const Measurement m = measure(p, GridParams{.sizes = r.sizes});
    std::printf("\nT/N predicted %.4g, counted %.4g (%llu contacts)\n", r.model.T_over_N, m.T_over_N,
                static_cast<unsigned long long>(m.counts.contacts));
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
