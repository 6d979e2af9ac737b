#include "hgridlab/measure/measurement.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "hgridlab/grid/dispatch.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/base/clock.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/grid/tilted.hpp"
#include "hgridlab/io/particle_file.hpp"
#include "hgridlab/model/cell_sizes.hpp"
#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/model.hpp"
#include "hgridlab/packing/packing_model.hpp"

namespace hgrid {
namespace {

/// The orthogonal grid that holds the cells (a tilted box's is its mapped one).
template <int D, Boundary B>
const HGrid<D, B>& mapped_grid(const HGrid<D, B>& g) { return g; }
template <int D>
const HGrid<D, Boundary::periodic>& mapped_grid(const TiltedHGrid<D>& g) { return g.mapped_grid(); }

/// Repeats build (make()) + uncounted query (each timed on its own) and
/// keeps the fastest; every run must find the counted search's pairs.
template <class MakeGrid>
void time_uncounted(MakeGrid make, const GridParams& g, const TimingOptions& opt, Measurement& m) {
  if (opt.min_repeats < 1 || opt.max_repeats < opt.min_repeats)
    throw InputError("repeat", "need 1 <= min_repeats <= max_repeats");
  struct alignas(64) Slot {  // pairs found per thread (one cache line each)
    std::uint64_t n = 0;
  };
  std::vector<Slot> found(static_cast<std::size_t>(resolve_threads(g.threads)));
  std::vector<double> queries;
  double total = 0, best_build = 1e300;
  while (static_cast<int>(queries.size()) < opt.max_repeats &&
         (static_cast<int>(queries.size()) < opt.min_repeats || total < opt.min_seconds)) {
    auto t0 = Clock::now();
    const auto grid = make();
    best_build = std::min(best_build, seconds_since(t0));
    for (auto& f : found) f.n = 0;
    t0 = Clock::now();
    grid.for_each_pair([&found](int t, std::uint32_t, std::uint32_t) { ++found[static_cast<std::size_t>(t)].n; });
    const double t = seconds_since(t0);
    std::uint64_t pairs = 0;
    for (const auto& f : found) pairs += f.n;
    if (pairs != m.counts.contacts) throw std::logic_error("measure: uncounted and counted searches found different pairs");
    queries.push_back(t);
    total += t;
  }
  std::sort(queries.begin(), queries.end());
  m.repeats = static_cast<int>(queries.size());
  m.seconds_query_best = queries.front();
  m.seconds_query_median = queries[queries.size() / 2];
  m.seconds_build_best = best_build;
}

/// A tilted box's grid searches the mapped packing (grid/tilted.hpp): its
/// spheres c times larger in the orthogonal box of the same lengths, with
/// cell sizes c times larger; the random-centres model of that packing
/// (packing fraction c^d nu, above 1 for dense sheared packings: random
/// centres, so allowed) is the model of the work (docs/MODEL.md section 12).
/// The excluded-volume model describes spheres, not the mapped ellipsoids:
/// not computed.
void add_tilted_model(const Packing& p, const MeasureOptions& o, Measurement& m) {
  const double c = m.tilt_inflation;
  std::vector<double> radii = p.radii;
  for (auto& r : radii) r *= c;
  const Empirical dist(radii);
  std::vector<double> sizes = sizes_for_grid(m.sizes, 2 * Empirical(p.radii).r_max());
  for (auto& s : sizes) s *= c;
  if (o.excluded_model) m.model_excluded_skipped = "a tilted box (the model is for spheres in the grid; see docs/MODEL.md section 12)";
  ModelParams mp{p.d, std::pow(c, p.d) * p.packing_fraction(), o.K, m.search};
  mp.overfull = true;
  try {
    const ModelResult r = evaluate_model(dist, mp, sizes);
    m.model_T_over_N = r.T_over_N;
    m.model_T_cd_over_N = r.T_cd_over_N;
    m.model_T_ca_over_N = r.T_ca_over_N;
    for (const double v : r.T_cd_pair) m.model_checks_by_level.push_back(static_cast<double>(m.n) * v);
  } catch (const InputError& e) {
    m.model_skipped = std::string("the tilted box's mapped spheres (grid/tilted.hpp): ") + e.what();
  }
}

void add_models(const Packing& p, const MeasureOptions& o, Measurement& m) {
  if (p.tilted()) return add_tilted_model(p, o, m);
  const Empirical dist(p.radii);
  const std::vector<double> sizes = sizes_for_grid(m.sizes, 2 * dist.r_max());
  const PackingModels pm =
      model_for_packing(p, sizes, m.search, o.K,
                        {o.excluded_model, o.model_progress, o.wall_pairs, o.excluded_work_budget});
  const double n = static_cast<double>(m.n);
  const auto checks = [n](const std::vector<double>& per_particle) {
    std::vector<double> out;
    for (const double v : per_particle) out.push_back(n * v);
    return out;
  };
  m.model_T_over_N = pm.random.T_over_N;
  m.model_T_cd_over_N = pm.random.T_cd_over_N;
  m.model_T_ca_over_N = pm.random.T_ca_over_N;
  m.model_checks_by_level = checks(pm.random.T_cd_pair);
  if (!o.excluded_model) return;
  if (p.boundary == Boundary::walls) m.wall_pairs = o.wall_pairs;
  if (!pm.excluded) {
    m.model_excluded_skipped = pm.excluded_skipped;
    return;
  }
  m.model_excluded_T_over_N = pm.excluded->T_over_N;
  m.model_excluded_T_cd_over_N = pm.excluded->T_cd_over_N;
  m.model_excluded_T_ca_over_N = pm.excluded->T_ca_over_N;
  m.model_excluded_checks_by_level = checks(pm.excluded->T_cd_pair);
}

void add_predicted_seconds(const Packing& p, const MeasureOptions& o, Measurement& m) {
  m.time_model = o.time_model_source;
  const Empirical dist(p.radii);
  const ModelParams mp{p.d, m.nu_achieved, o.K, m.search};
  const PredictedSeconds c = predict_seconds(*o.time_model, counted_time_terms(m.counts, m.build_work));
  if (!p.tilted()) {  // the expected terms are the orthogonal grid's; a tilted box has its counts only
    const PredictedSeconds e =
        predict_seconds(*o.time_model, expected_time_terms(dist, mp, m.sizes, static_cast<double>(m.n)));
    m.predicted_seconds_build_one_thread = e.build;
    m.predicted_seconds_query_one_thread = e.query;
  }
  m.predicted_seconds_build_one_thread_from_counts = c.build;
  m.predicted_seconds_query_one_thread_from_counts = c.query;
}

}  // namespace

void record_counts(Measurement& m, Counters c, double K) {
  m.counts = std::move(c);
  const double n = static_cast<double>(m.n);
  m.T_over_N = m.n ? m.counts.cost(K) / n : 0.0;
  m.T_cd_over_N = m.n ? static_cast<double>(m.counts.narrow_phase_checks) / n : 0.0;
  m.T_ca_over_N = m.n ? static_cast<double>(m.counts.cell_accesses) / n : 0.0;
}

Predictions parse_predictions(const std::string& s, const std::string& field) {
  if (s == "none") return Predictions::none;
  if (s == "paper") return Predictions::paper;
  if (s == "excluded") return Predictions::excluded;
  throw InputError(field, "must be none, paper or excluded (got '" + s + "')");
}

Measurement measure(const Packing& p, const GridParams& g, const MeasureOptions& o) {
  if (p.size() == 0) throw InputError("packing", "no particles to measure");
  Measurement m;
  m.n = p.size();
  m.d = p.d;
  m.boundary = p.boundary;
  const auto src = p.str_attrs.find(kBoundarySourceAttr);
  m.boundary_assumed = src != p.str_attrs.end() && src->second == kBoundaryAssumed;
  m.nu_achieved = p.packing_fraction();
  m.search = g.search;
  m.threads = resolve_threads(g.threads);
  m.K = o.K;
  m.sizes_requested = g.sizes;
  // The counted search, the sizes as used, the occupancy, the timings: on
  // the grid make() builds (the HGrid, or a tilted box's, grid/tilted.hpp).
  const auto on_grid = [&](auto make) {
    auto t0 = Clock::now();
    const auto grid = make();
    m.seconds_build = seconds_since(t0);
    t0 = Clock::now();
    record_counts(m, grid.template for_each_pair<Counted>([](std::uint32_t, std::uint32_t) {}), o.K);
    m.seconds_query = seconds_since(t0);
    m.sizes = grid.sizes();
    const auto& orthogonal = mapped_grid(grid);
    m.build_work = build_work(orthogonal);
    if (o.occupancy) {
      const auto occ = orthogonal.occupancy(0);
      m.share_multi_lowest = static_cast<double>(occ[2]) / static_cast<double>(occ[0] + occ[1] + occ[2]);
    }
    if (o.timing) time_uncounted(make, g, *o.timing, m);
  };
  dispatch(p.d, p.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    constexpr Boundary B = decltype(bnd)::value;
    const auto spheres = p.spheres<D>();
    if (p.tilted()) {
      m.tilt = tilt_values(p.tilt, D);
      m.tilt_inflation = p.tilted_box<D>().inflation();
      on_grid([&] { return TiltedHGrid<D>(spheres, p.tilted_box<D>(), g); });
    } else {
      on_grid([&] { return HGrid<D, B>(spheres, p.extent<D>(), g); });
    }
  });
  if (o.model) add_models(p, o, m);
  if (o.time_model) add_predicted_seconds(p, o, m);
  return m;
}

}  // namespace hgrid
