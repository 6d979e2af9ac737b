#include "hgridlab/packing/packing_model.hpp"

#include "hgridlab/base/error.hpp"
#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/excluded.hpp"
#include "hgridlab/base/progress.hpp"

namespace hgrid {

PackingModels model_for_packing(const Packing& p, const std::vector<double>& sizes, Search search, double K,
                                const PackingModelOptions& opt) {
  if (p.size() == 0) throw InputError("packing", "no particles to model");
  const Empirical dist(p.radii);
  const ModelParams mp{p.d, p.packing_fraction(), K, search};
  PackingModels out;
  out.random = evaluate_model(dist, mp, sizes);
  if (!opt.excluded) {
    out.excluded_skipped = "not requested";
  } else if (!(mp.nu < 1.0)) {
    out.excluded_skipped = "packing fraction >= 1";
  } else {
    try {
      std::optional<WallBox> walls;
      if (p.boundary == Boundary::walls) walls = WallBox{{p.box[0], p.box[1], p.box[2]}};
      out.excluded = evaluate_excluded_model_reported(dist, mp, sizes, walls, opt.progress, opt.wall_pairs,
                                                       opt.disc_work_budget);
    } catch (const InputError& e) {
      out.excluded_skipped = e.what();
    }
  }
  return out;
}

ModelResult evaluate_excluded_model_reported(const Distribution& dist, const ModelParams& p,
                                             const std::vector<double>& sizes, const std::optional<WallBox>& walls,
                                             bool progress, WallPairs wall_pairs, double disc_work_budget) {
  Progress bar(progress && p.d == 2,
               "excluded-volume model (2D Percus-Yevick, ETA for at most " + std::to_string(kMaxDiscIterations) + " iterations)");
  ExcludedOptions opt;
  opt.wall_pairs = wall_pairs;
  opt.disc_work_budget = disc_work_budget;
  opt.on_iteration = [&](double t, int it) {
    bar.update(static_cast<double>(it) / kMaxDiscIterations,
               "density " + std::to_string(static_cast<int>(100 * t)) + " %, " + std::to_string(it) + " iterations");
  };
  return evaluate_excluded_model(dist, p, sizes, opt, walls);
}

}  // namespace hgrid
