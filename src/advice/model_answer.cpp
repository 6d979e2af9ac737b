#include "hgridlab/advice/model_answer.hpp"

#include <nlohmann/json.hpp>

#include "hgridlab/base/error.hpp"
#include "hgridlab/base/printf.hpp"
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

std::string model_answer_json(const ModelAnswer& a, const ModelQuestion& q) {
  const ModelResult& m = a.model;
  nlohmann::json j;
  j["levels"] = a.levels;
  j["sizes"] = a.sizes;
  j["T_over_N"] = m.T_over_N;
  j["T_cd_over_N"] = m.T_cd_over_N;
  j["T_ca_over_N"] = m.T_ca_over_N;
  if (q.excluded) j["T_over_N_random"] = a.random.T_over_N;
  if (a.seconds) {
    j["predicted_seconds_build"] = a.seconds->build;
    j["predicted_seconds_query"] = a.seconds->query;
    j["n"] = q.n;
  }
  if (q.excluded_sizes) {
    j["T_over_N_excluded_paper_sizes"] = a.T_over_N_excluded_paper_sizes;
    j["excluded_size_evaluations"] = a.excluded_size_evaluations;
  }
  j["T_cd_per_level"] = m.T_cd;
  j["P"] = m.P;
  j["m"] = m.m;
  return j.dump();
}

std::string model_answer_text(const ModelAnswer& a, const ModelQuestion& q) {
  const ModelResult& m = a.model;
  std::string out = printf_string("levels L = %d (%s)\nT/N = %.6f  (T_cd/N = %.6f, T_ca/N = %.6f, K = %g)%s\n",
                                  a.levels, q.levels ? "given" : "best L*", m.T_over_N, m.T_cd_over_N, m.T_ca_over_N,
                                  q.params.K, q.excluded ? "  excluded-volume model" : "");
  if (a.seconds)
    out += printf_string("sizes minimise this machine's predicted seconds for N = %g: build %.4g s + query %.4g s\n",
                         q.n, a.seconds->build, a.seconds->query);
  if (q.excluded && !q.excluded_sizes)
    out += printf_string("random-centre model for the same sizes: T/N = %.6f\n", a.random.T_over_N);
  if (q.excluded_sizes)
    out += printf_string(
        "sizes refined under the excluded-volume model (%d evaluations); with the paper's sizes T/N = %.6f\n",
        a.excluded_size_evaluations, a.T_over_N_excluded_paper_sizes);
  out += printf_string("%5s %14s %12s %12s\n", "h", "s_h/r_min", "P_h", "m_h");
  for (int h = 0; h < a.levels; ++h)
    out += printf_string("%5d %14.6g %12.6g %12.6g\n", h + 1, a.sizes[h], m.P[h], m.m[h]);
  return out;
}

}  // namespace hgrid
