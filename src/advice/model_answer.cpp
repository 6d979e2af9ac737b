#include "hgridlab/advice/model_answer.hpp"

#include "hgridlab/base/error.hpp"
#include "hgridlab/model/excluded.hpp"
#include "hgridlab/packing/packing.hpp"
#include "hgridlab/packing/packing_model.hpp"
#include "hgridlab/packing/packing_sizes.hpp"

namespace hgrid {

ModelAnswer answer_model(const Distribution& dist, const ModelQuestion& q) {
  const ModelParams& p = q.params;
  validate(p);
  if (q.levels && *q.levels < 1) throw InputError("levels", "must be >= 1 (got " + std::to_string(*q.levels) + ")");
  if (q.excluded_sizes && !q.excluded) throw InputError("excluded-sizes", "needs --placement excluded");
  auto choice = choose_cell_sizes(dist, p, q.cells, q.levels, q.q);
  ModelAnswer a;
  if (q.cost == CostKind::time) {  // this machine's time optimum replaces the count one
    if (q.cells != CellMethod::optimal || q.levels || q.excluded_sizes)
      throw InputError("cost", "'time' needs --cells optimal, without --levels or --excluded-sizes");
    if (!(q.n >= 1 && q.n <= double(kMaxParticles))) throw InputError("n", "must be in [1, 2^31 - 1]");
    const TimeOptimalSizes t = time_optimal_sizes(dist, p, calibrated_time_model(p.d, "cost").coef, q.n);
    choice.sizes = t.sizes;
    choice.levels = static_cast<int>(t.sizes.size());
    choice.model = evaluate_model(dist, p, t.sizes);
    a.seconds = t.seconds;
  }
  a.levels = choice.levels;
  a.random = choice.model;
  std::vector<double> sizes = choice.sizes;
  // The paper's model (random centres) chooses the sizes; for hard spheres
  // the excluded-volume model is evaluated for the same sizes, or refines them.
  a.model = q.excluded ? evaluate_excluded_model_reported(dist, p, sizes) : choice.model;
  a.T_over_N_excluded_paper_sizes = a.model.T_over_N;
  if (q.excluded_sizes) {
    const ExcludedSizes r = refine_sizes_excluded_reported(dist, p, sizes);
    a.model = r.model;
    a.excluded_size_evaluations = r.evaluations;
    sizes = r.sizes;
  }
  for (double s : sizes) a.sizes.push_back(s / dist.r_min());
  return a;
}

}  // namespace hgrid
