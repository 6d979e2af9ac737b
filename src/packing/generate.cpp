#include "hgridlab/packing/generate.hpp"
#include "hgridlab/packing/identity.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <numeric>
#include <optional>
#include <string>

#include "hgridlab/base/threads.hpp"
#include "hgridlab/packing/detail/gen_common.hpp"
#include "hgridlab/packing/detail/gen_equilibrate.hpp"
#include "hgridlab/packing/detail/gen_record.hpp"
#include "hgridlab/packing/detail/gen_relax.hpp"
#include "hgridlab/packing/detail/gen_rsa.hpp"
#include "hgridlab/packing/detail/gen_stationary.hpp"
#include "hgridlab/grid/dispatch.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/packing/packing_sizes.hpp"
#include "hgridlab/packing/rcp.hpp"

namespace hgrid {

using detail::is_placement;
using detail::kGeneratorVersion;
using detail::join_series;
using detail::kChainAttr;
using detail::kRngAttr;
using detail::kSeriesAttr;
using detail::kTallyAttrs;
using detail::recorded_series;

namespace {

/// Packing fraction at which the growth route starts its sequential addition.
constexpr double kGrowthStartNu = 0.35;
/// The largest box nu of a bed (placement bed): its particles settle to a
/// packing of ~0.6, so that a bed fills at most about half of its box.
constexpr double kBedMaxNu = 0.3;
/// A bed is first packed at this share of the random close packing estimate
/// (rcp.hpp) in the bottom of its box, then settled.
constexpr double kBedRcpShare = 0.85;
/// Achieved nu must match the request to this relative error.

/// Short text for messages.
std::string brief(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

void check_spec(const PackingSpec& s) {
  if (s.d != 2 && s.d != 3) throw InputError("d", "must be 2 or 3 (got " + std::to_string(s.d) + ")");
  if (s.n == 0 || s.n > 0x7fffffffu) throw InputError("n", "must be in [1, 2^31 - 1] (got " + std::to_string(s.n) + ")");
  if (!(std::isfinite(s.nu) && s.nu > 0 && s.nu < 1)) throw InputError("nu", "must be in (0, 1) (got " + brief(s.nu) + ")");
  if (s.equilibrate && s.placement != Placement::excluded)
    throw InputError("equilibrate", "only applies to excluded-volume placement");
  if (s.placement == Placement::bed && s.boundary != Boundary::walls)
    throw InputError("boundary", "a bed (placement 'bed') needs walls: it rests on the floor of the last axis");
  if (s.placement == Placement::bed && s.nu > kBedMaxNu)
    throw InputError("nu", "a bed fills part of its box: the box's nu must be at most " + brief(kBedMaxNu) +
                               " (got " + brief(s.nu) + ")");
  if (s.method != ExcludedMethod::automatic && s.placement != Placement::excluded)
    throw InputError("method", "only applies to excluded-volume placement");
  if (s.stop != EquilibrationStop::sweeps && !s.equilibrate)
    throw InputError("stop", "only applies to an equilibration (equilibrate)");
  if (s.moves != EquilibrationMoves::metropolis && !s.equilibrate)
    throw InputError("moves", "only applies to an equilibration (equilibrate)");
  if (s.moves == EquilibrationMoves::event_chain && s.boundary != Boundary::periodic)
    throw InputError("moves", "'event-chain' needs a periodic box (a chain cannot be passed to a wall)");
  if (!(s.stationary_tol > 0 && s.stationary_tol <= 0.1))
    throw InputError("stationary_tol", "must be in (0, 0.1] (got " + brief(s.stationary_tol) + ")");
  check_threads(s.threads);
  if (s.sweeps < 1 || s.sweeps > kMaxEquilibrationSweeps)
    throw InputError("sweeps", "must be in [1, " + std::to_string(kMaxEquilibrationSweeps) + "] (got " +
                                   std::to_string(s.sweeps) + ")");
}

/// Radii (draw order) and the cubic box side for exactly spec.nu.
double draw_radii(const PackingSpec& s, const Distribution& dist, detail::GenRng& rng, std::vector<double>& radii) {
  radii.resize(s.n);
  double volume = 0;
  for (auto& r : radii) {
    r = dist.quantile(rng.uniform());
    volume += unit_ball_volume(s.d) * std::pow(r, s.d);
  }
  return std::pow(volume / s.nu, 1.0 / s.d);
}

void place_random(const PackingSpec& s, detail::GenRng& rng, Packing& p) {
  const double side = p.box[0];
  for (std::size_t i = 0; i < s.n; ++i) {
    const double r = p.radii[i];
    const double margin = s.boundary == Boundary::walls ? r : 0.0;
    if (2 * margin > side)
      throw InputError("nu", "too high for walls: a particle of diameter " + brief(2 * r) +
                                 " does not fit the box of side " + brief(side));
    for (int a = 0; a < s.d; ++a) p.positions[i * s.d + a] = margin + rng.uniform() * (side - 2 * margin);
  }
}

std::string unreachable(const PackingSpec& s, double rcp, const std::string& why) {
  return why + "; the estimated highest reachable nu (random close packing, de Larrard linear packing model) for this " +
         "distribution is " + brief(std::round(rcp * 1e4) / 1e4) + " (requested " + brief(s.nu) + ")";
}

/// FIRE's threads (growth, settling): at most one per kRelaxMinSpheresPerThread spheres.
int relax_threads(const PackingSpec& s) {
  return static_cast<int>(std::clamp<std::size_t>(s.n / detail::kRelaxMinSpheresPerThread, 1,
                                                  static_cast<std::size_t>(resolve_threads(s.threads))));
}

void place_excluded(const PackingSpec& s, double rcp, detail::GenRng& rng, Packing& p) {
  const double side = p.box[0];
  const double rmax = *std::max_element(p.radii.begin(), p.radii.end());
  const double need = s.boundary == Boundary::walls ? 2 * rmax : 4 * rmax;
  if (side < need)
    throw InputError("n", "too small: the box side " + brief(side) + " must be at least " + brief(need) +
                              " (" + (s.boundary == Boundary::walls ? "2" : "4") +
                              " largest radii) for excluded-volume placement; increase n");
  std::vector<std::uint32_t> order(s.n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return p.radii[a] > p.radii[b]; });
  Progress progress(s.progress, "excluded-volume placement (sequential addition)");
  const std::size_t placed =
      s.method == ExcludedMethod::growth
          ? 0
          : detail::rsa_place(s.d, s.boundary, p.box, p.radii, order, 1.0, resolve_threads(s.threads), rng,
                              p.positions, progress);
  if (placed == s.n) {
    p.str_attrs["method"] = "rsa";
    return;
  }
  if (s.method == ExcludedMethod::rsa)
    throw InputError("method", unreachable(s, rcp, "sequential addition stalls after " + std::to_string(placed) +
                                                       " of " + std::to_string(s.n) + " particles (method 'rsa')"));
  if (s.progress && s.method == ExcludedMethod::automatic)
    std::fprintf(stderr, "  sequential addition stalled after %zu of %zu particles; growing from nu = %g instead\n",
                 placed, s.n, std::min(s.nu, kGrowthStartNu));
  // Growth route: sequential addition at a lower nu, then grow and relax.
  double nu0 = std::min(s.nu, kGrowthStartNu);
  double scale0 = 1;
  for (int tries = 0;; ++tries) {
    scale0 = std::pow(nu0 / s.nu, 1.0 / s.d);
    Progress p0(s.progress, "sequential addition at nu = " + brief(nu0));
    if (detail::rsa_place(s.d, s.boundary, p.box, p.radii, order, scale0, resolve_threads(s.threads), rng, p.positions,
                          p0) == s.n)
      break;
    if (tries == 5) throw InputError("nu", unreachable(s, rcp, "sequential addition stalls even at nu = " + brief(nu0)));
    nu0 *= 0.8;
  }
  Progress progress2(s.progress, "growth + FIRE relaxation");
  detail::RelaxStats st;
  if (!detail::grow_and_relax(s.d, s.boundary, p.box, p.radii, scale0, relax_threads(s), p.positions, progress2, st)) {
    const double reached = s.nu * std::pow(std::pow(detail::kGrowthStep, st.growth_steps) * scale0, s.d);
    throw InputError("nu", unreachable(s, rcp, "the growth did not converge within its FIRE step budget (reached nu ≈ " +
                                                   brief(std::round(std::min(reached, s.nu) * 1e4) / 1e4) + " after " +
                                                   std::to_string(st.fire_steps) + " steps)"));
  }
  p.str_attrs["method"] = "rsa+growth+fire";
  p.num_attrs["growth_start_nu"] = nu0;
  p.num_attrs["fire_steps"] = static_cast<double>(st.fire_steps);
  p.num_attrs["growth_steps"] = st.growth_steps;
  p.num_attrs["neighbour_list_builds"] = st.list_builds;
}


/// Placement bed: an excluded-volume packing at kBedRcpShare of the random
/// close packing estimate in the bottom of the box (the box's height cut to
/// what that takes, walls on every side), then the lid lifted to the box's
/// top and the spheres settled under gravity.
void place_bed(const PackingSpec& s, double rcp, detail::GenRng& rng, Packing& p) {
  PackingSpec dense = s;
  dense.nu = std::min(kBedRcpShare * rcp, 0.999);
  const double top = p.box[s.d - 1];
  p.box[s.d - 1] = top * s.nu / dense.nu;
  place_excluded(dense, rcp, rng, p);
  p.box[s.d - 1] = top;
  p.num_attrs["bed_packing_fraction"] = dense.nu;
  Progress progress(s.progress, "settling under gravity (FIRE)");
  detail::RelaxStats st;
  if (!detail::settle_under_gravity(s.d, p.box, p.radii, relax_threads(s), p.positions, progress, st))
    throw InputError("n", "the bed did not settle within its FIRE step budget (" + std::to_string(st.fire_steps) +
                              " steps); fewer particles or a smaller size ratio");
  p.str_attrs["method"] += "+settled";
  p.num_attrs["settle_fire_steps"] = static_cast<double>(st.fire_steps);
}

}  // namespace

ExcludedMethod parse_excluded_method(const std::string& s, const std::string& field) {
  if (s == "auto") return ExcludedMethod::automatic;
  if (s == "rsa") return ExcludedMethod::rsa;
  if (s == "growth") return ExcludedMethod::growth;
  throw InputError(field, "must be 'auto', 'rsa' or 'growth' (got '" + s + "')");
}

EquilibrationMoves parse_equilibration_moves(const std::string& s, const std::string& field) {
  if (s == "metropolis") return EquilibrationMoves::metropolis;
  if (s == "event-chain") return EquilibrationMoves::event_chain;
  throw InputError(field, "must be 'metropolis' or 'event-chain' (got '" + s + "')");
}

EquilibrationStop parse_equilibration_stop(const std::string& s, const std::string& field) {
  if (s == "sweeps") return EquilibrationStop::sweeps;
  if (s == "stationary") return EquilibrationStop::stationary;
  throw InputError(field, "must be 'sweeps' or 'stationary' (got '" + s + "')");
}

Placement parse_placement(const std::string& s, const std::string& field) {
  if (s == "random") return Placement::random;
  if (s == "excluded") return Placement::excluded;
  if (s == "bed") return Placement::bed;
  throw InputError(field, "must be 'random', 'excluded' or 'bed' (got '" + s + "')");
}

std::unique_ptr<Distribution> make_distribution(const PackingSpec& s) {
  if (!(std::isfinite(s.omega) && s.omega >= 1 && s.omega <= 1e6))
    throw InputError("omega", "must be in [1, 1e6] (got " + brief(s.omega) + ")");
  if (s.dist == "powerlaw") {
    if (!(std::isfinite(s.alpha) && std::abs(s.alpha) <= 20))
      throw InputError("alpha", "must be in [-20, 20] (got " + brief(s.alpha) + ")");
    return std::make_unique<PowerLaw>(s.alpha, s.omega);
  }
  if (s.dist == "lognormal") {
    if (!(std::isfinite(s.sigma) && s.sigma > 0 && s.sigma <= 10))
      throw InputError("sigma", "must be in (0, 10] (got " + brief(s.sigma) + ")");
    return std::make_unique<LogNormal>(LogNormal::centred(s.sigma, s.omega));
  }
  throw InputError("dist", "must be 'powerlaw' or 'lognormal' (got '" + s.dist + "')");
}

std::unique_ptr<Distribution> recorded_distribution(const Packing& p) {
  const auto dist = p.str_attrs.find("dist");
  if (dist == p.str_attrs.end() || !p.num_attrs.count("omega")) return nullptr;
  PackingSpec s;
  s.dist = dist->second;
  s.omega = p.num_attrs.at("omega");
  if (p.num_attrs.count("alpha")) s.alpha = p.num_attrs.at("alpha");
  if (p.num_attrs.count("sigma")) s.sigma = p.num_attrs.at("sigma");
  try {
    return make_distribution(s);
  } catch (const InputError&) {
    return nullptr;
  }
}


double check_packing_spec(const PackingSpec& s) {
  check_spec(s);
  check_memory("n", s.n,
               s.placement == Placement::random ? kGenerateRandomBytesPerParticle : kGenerateBytesPerParticle,
               "generating a packing");
  const auto dist = make_distribution(s);
  const double rcp = estimate_rcp(s.d, *dist);
  if (excludes_volume(s.placement) && s.nu > rcp)
    throw InputError("nu", unreachable(s, rcp, "beyond jamming for excluded-volume placement"));
  return rcp;
}

namespace {


/// The stationarity observable's state during an equilibration.
struct StopState {
  std::vector<double> sizes;   // the grid's cell sizes (the packing's own optimal Top-Down sizes)
  std::vector<double> series;  // T/N every kStationarySampleSweeps sweeps
  detail::Stationarity last;   // the test after the last sample
};



/// T/N = (narrow-phase checks + K cell accesses) / N of the counted HGrid
/// search of p with these sizes (Top-Down, K = kStationaryK); the counts
/// alone (CountsOnly: the same counts as Counted, no pair tested).
double counted_T_over_N(const Packing& p, const std::vector<double>& sizes, int threads) {
  double t = 0;
  dispatch(p.d, p.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    constexpr Boundary B = decltype(bnd)::value;
    auto spheres = p.spheres<D>();
    if constexpr (B == Boundary::periodic)  // the Monte Carlo's moves wrap; a start may lie on the far face
      for (auto& sp : spheres)
        for (int k = 0; k < D; ++k) sp.x[k] = detail::wrap(sp.x[k], p.box[k]);
    const HGrid<D, B> grid(spheres, p.extent<D>(), GridParams{sizes, Search::top_down, threads});
    t = grid.template for_each_pair<CountsOnly>([](std::uint32_t, std::uint32_t) {}).cost(kStationaryK) /
        static_cast<double>(p.size());
  });
  return t;
}

/// Spec, achieved nu and quality attributes of p, generated for s (with
/// e.sweeps sweeps so far when s.equilibrate; rng: the generator's state
/// then, recorded for every excluded-volume packing: a placement is where
/// each equilibration of it starts).
void describe(Packing& p, const PackingSpec& s, const Distribution& dist, double rcp, const detail::Equilibration& e,
              const detail::GenRng& rng, const StopState* stop = nullptr, bool final = false) {
  PackingSpec at = s;
  if (excludes_volume(s.placement)) p.str_attrs[kRngAttr] = rng.state();
  if (s.equilibrate) {
    // A stage part-way is the chain at e.sweeps; the end of a run that
    // stopped when stationary is the packing its spec (cap) names.
    if (!(final && s.stop == EquilibrationStop::stationary)) at.sweeps = static_cast<int>(e.sweeps);
    p.str_attrs["equilibration_stop"] = to_string(s.stop);
    p.str_attrs["equilibration_moves"] = to_string(s.moves);
    if (stop) {
      p.str_attrs[kSeriesAttr] = join_series(stop->series);
      p.num_attrs["stationarity_sample_sweeps"] = detail::kStationarySampleSweeps;
      p.num_attrs["stationarity_rel_tol"] = s.stationary_tol;
      p.num_attrs["stationarity_K"] = kStationaryK;
      p.str_attrs["stationarity_observable"] = "T/N, optimal Top-Down sizes, K = 0.2";
      p.str_attrs["stationarity_rule"] = detail::stationarity_rule(s.stationary_tol, stationary_floor(s));
      p.num_attrs["stationarity_mean"] = stop->last.mean;
      p.num_attrs["stationarity_drift_per_doubling"] = stop->last.drift;
      p.num_attrs["stationarity_drift_se"] = stop->last.se;
      p.num_attrs["stationarity_samples"] = static_cast<double>(stop->last.samples);
      p.num_attrs["stationarity_reached"] = stop->last.stationary ? 1 : 0;
    }
    p.num_attrs["equilibration_acceptance"] = e.displacement_acceptance();
    p.num_attrs["equilibration_swap_acceptance"] = e.swap_acceptance();
    p.num_attrs["equilibration_sweeps"] = static_cast<double>(e.sweeps);
    const std::uint64_t tally[4] = {e.moves_accepted, e.moves_proposed, e.swaps_accepted, e.swaps_proposed};
    for (int k = 0; k < 4; ++k) p.num_attrs[kTallyAttrs[k]] = static_cast<double>(tally[k]);
    p.str_attrs[kChainAttr] = equilibration_chain_key(s);
  }
  p.str_attrs["placement"] = to_string(s.placement);
  p.str_attrs["dist"] = s.dist;
  p.str_attrs["cache_key"] = packing_key(at);
  p.str_attrs["seed_str"] = std::to_string(s.seed);
  p.num_attrs["seed"] = static_cast<double>(s.seed);
  p.num_attrs["n"] = static_cast<double>(s.n);
  p.num_attrs["nu"] = s.nu;
  p.num_attrs["omega"] = s.omega;
  if (s.dist == "lognormal") p.num_attrs["sigma"] = s.sigma;
  else p.num_attrs["alpha"] = s.alpha;
  p.num_attrs["equilibrate"] = s.equilibrate ? 1 : 0;
  p.num_attrs["generator_version"] = kGeneratorVersion;
  p.num_attrs["rcp_estimate"] = rcp;
  // Overlap figures only for excluded volume (random centres overlap anyway,
  // and a contact search would cost more than the placement itself).
  const bool excluded = excludes_volume(s.placement);
  const PackingQuality q = assess_packing(p, &dist, excluded);
  p.num_attrs["nu_achieved"] = q.nu;
  if (excluded) {
    p.num_attrs["max_rel_overlap"] = q.max_rel_overlap;
    p.num_attrs["mean_rel_overlap"] = q.mean_rel_overlap;
    p.num_attrs["mean_contacts"] = q.mean_contacts;
  }
  p.num_attrs["slab_max_dev"] = q.slab_max_dev;
  p.num_attrs["ks_distance"] = q.ks_distance;
  p.num_attrs["ks_pvalue"] = q.ks_pvalue;
  if (std::abs(q.nu / s.nu - 1) > kNuRelTol)
    throw std::logic_error("generate_packing: achieved nu " + format_number(q.nu) + " differs from " + format_number(s.nu));
}


}  // namespace



Packing generate_packing(const PackingSpec& s, const Packing* from, const PackingCheckpoint& checkpoint) {
  const double rcp = check_packing_spec(s);
  const auto dist = make_distribution(s);
  detail::GenRng rng(s.seed);
  detail::Equilibration e;
  Packing p;
  if (from) {
    const std::string why = resume_mismatch(*from, s);
    if (!why.empty()) throw std::invalid_argument("generate_packing: cannot resume from that packing: " + why);
    p = *from;
    if (!rng.restore(from->str_attrs.at(kRngAttr)))
      throw std::invalid_argument("generate_packing: cannot resume: unreadable random generator state");
    e.sweeps = equilibration_sweeps_done(*from);
    std::uint64_t* tally[4] = {&e.moves_accepted, &e.moves_proposed, &e.swaps_accepted, &e.swaps_proposed};
    if (!is_placement(*from))
      for (int k = 0; k < 4; ++k) *tally[k] = static_cast<std::uint64_t>(from->num_attrs.at(kTallyAttrs[k]));
  } else {
    p.d = s.d;
    p.boundary = s.boundary;
    const double side = draw_radii(s, *dist, rng, p.radii);
    for (int a = 0; a < s.d; ++a) p.box[a] = side;
    p.positions.assign(s.n * s.d, 0.0);
    if (s.placement == Placement::random) place_random(s, rng, p);
    else if (s.placement == Placement::excluded) place_excluded(s, rcp, rng, p);
    else place_bed(s, rcp, rng, p);
  }
  std::optional<StopState> stop;  // stop = stationary: the observable's state
  if (s.equilibrate) {
    detail::EquilibrationObserver observe;
    if (s.stop == EquilibrationStop::stationary) {
      stop.emplace();
      SizeRequest req;  // the figures' sizes: optimal, Top-Down, K = 0.2
      stop->sizes = model_sizes(p, req, Search::top_down, kStationaryK);
      if (from && !is_placement(*from)) stop->series = *recorded_series(*from);
      const int count_threads = resolve_threads(s.threads);
      observe = [&, count_threads](const detail::Equilibration& at, std::string& extra) {
        if (at.sweeps % detail::kStationarySampleSweeps) return false;
        stop->series.push_back(counted_T_over_N(p, stop->sizes, count_threads));
        stop->last = detail::test_stationary(stop->series, s.stationary_tol, stationary_floor(s));
        char buf[96];
        std::snprintf(buf, sizeof buf, ", T/N %.4f, drift/doubling %+.2f %%", stop->series.back(),
                      stop->last.mean > 0 ? 100 * stop->last.drift / stop->last.mean : 0.0);
        extra = buf;
        return stop->last.stationary;
      };
    }
    Progress progress(s.progress, "hard-sphere Monte Carlo equilibration" +
                                      (!from ? std::string()
                                       : e.sweeps == 0 ? std::string(" (from the given placement)")
                                                       : " (resumed at sweep " + std::to_string(e.sweeps) + ")"));
    detail::EquilibrationCheckpoint save;
    if (checkpoint)
      save = [&](const detail::Equilibration& at) {
        Packing c = p;  // positions as after at.sweeps sweeps
        describe(c, s, *dist, rcp, at, rng, stop ? &*stop : nullptr);
        checkpoint(c);
      };
    detail::equilibrate(s.d, s.boundary, s.moves == EquilibrationMoves::event_chain, p.box, p.radii, p.positions,
                        static_cast<std::uint64_t>(s.sweeps), s.threads, rng, progress, e, save, s.checkpoint_seconds,
                        observe, s.overlap_search);
  }
  if (s.boundary == Boundary::periodic)
    for (std::size_t i = 0; i < p.positions.size(); ++i) p.positions[i] = detail::wrap(p.positions[i], p.box[i % s.d]);
  describe(p, s, *dist, rcp, e, rng, stop ? &*stop : nullptr, true);
  return p;
}

Packing random_packing(const RandomSpec& r, const Distribution& dist) {
  check_spec(PackingSpec{.d = r.d, .n = r.n, .nu = r.nu});
  detail::GenRng rng(r.seed);
  Packing p;
  p.d = r.d;
  p.boundary = r.boundary;
  PackingSpec s{.d = r.d, .n = r.n, .nu = r.nu, .boundary = r.boundary, .seed = r.seed};
  const double side = draw_radii(s, dist, rng, p.radii);
  for (int a = 0; a < r.d; ++a) p.box[a] = side;
  p.positions.assign(r.n * r.d, 0.0);
  place_random(s, rng, p);
  p.str_attrs["placement"] = "random";
  p.num_attrs["seed"] = static_cast<double>(r.seed);
  p.num_attrs["nu"] = r.nu;
  p.num_attrs["nu_achieved"] = p.packing_fraction();
  return p;
}



}  // namespace hgrid
