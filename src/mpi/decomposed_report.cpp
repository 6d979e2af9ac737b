// The counted decomposed search as the one measurement record plus the
// decomposition's own fields (mpi/decomposed.hpp): what `hgrid count
// --decompose` prints, built here so that the tool only prints it.
#include <algorithm>
#include <nlohmann/json.hpp>
#include <string_view>

#include "hgridlab/base/printf.hpp"
#include "hgridlab/base/threads.hpp"
#include "hgridlab/measure/fields.hpp"
#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/model.hpp"
#include "hgridlab/mpi/comm.hpp"
#include "hgridlab/mpi/decomposed.hpp"

namespace hgrid::mpi {
namespace {

using json = nlohmann::ordered_json;

double shell_over_level_aware(const DecomposedRun& r) {
  return r.ghosts ? static_cast<double>(r.shell_ghosts) / static_cast<double>(r.ghosts) : 0.0;
}

std::uint64_t summed_rss(const DecomposedRun& r) {
  std::uint64_t rss = 0;
  for (const auto& k : r.ranks) rss += k.peak_rss_bytes;
  return rss;
}

double rss_per_particle(const DecomposedRun& r) {
  return r.n > 0 ? static_cast<double>(summed_rss(r)) / static_cast<double>(r.n) : 0.0;
}

}  // namespace

DecomposedCount decomposed_count(const std::string& file, const GridParams& g, double K) {
  DecomposedCount c;
  c.run = decomposed_search(file, g, true, nullptr);
  if (mpi::rank() != 0) return c;
  const DecomposedRun& r = c.run;
  Measurement& m = c.m;
  m.n = r.n;
  m.d = r.d;
  m.boundary = r.boundary;
  m.nu_achieved = r.packing_fraction;
  m.search = g.search;
  m.threads = resolve_threads(g.threads);
  m.K = K;
  m.sizes_requested = g.sizes;
  m.sizes = r.sizes;
  record_counts(m, r.work, K);
  const ModelResult model =
      evaluate_model(Empirical(r.radii_sample), ModelParams{r.d, r.packing_fraction, K, g.search}, r.sizes);
  m.model_T_over_N = model.T_over_N;
  m.model_T_cd_over_N = model.T_cd_over_N;
  m.model_T_ca_over_N = model.T_ca_over_N;
  return c;
}

std::string decomposed_count_json(const DecomposedCount& c) {
  const DecomposedRun& r = c.run;
  static constexpr std::string_view kFields[] = {
      "n", "d", "boundary", "nu_achieved", "search", "threads", "K", "sizes_requested", "sizes", "levels",
      "cell_accesses", "narrow_phase_checks", "contacts", "T_over_N", "T_cd_over_N", "T_ca_over_N",
      "model_T_over_N", "model_T_cd_over_N", "model_T_ca_over_N"};
  json j = json::parse(measurement_json(c.m, kFields));
  j["box"] = std::vector<double>(r.box.begin(), r.box.begin() + r.d);
  j["r_max"] = r.r_max;
  j["ranks"] = r.ranks.size();
  j["bricks"] = r.bricks;
  j["model_radii"] = r.radii_sample.size();
  j["ghosts"] = r.ghosts;
  j["shell_ghosts"] = r.shell_ghosts;
  j["shell_over_level_aware"] = shell_over_level_aware(r);
  j["halo_volume"] = r.halo_volume;
  j["halo_volume_shell"] = r.halo_volume_shell;
  double read = 0, exch = 0, build = 0, query = 0;
  json per_rank = json::array();
  for (const auto& k : r.ranks) {
    read = std::max(read, k.seconds_read), exch = std::max(exch, k.seconds_exchange);
    build = std::max(build, k.seconds_build), query = std::max(query, k.seconds_query);
    per_rank.push_back({{"rank", k.rank}, {"owned", k.owned}, {"ghosts", k.ghosts},
                        {"shell_ghosts", k.shell_ghosts}, {"seconds_read", k.seconds_read},
                        {"seconds_exchange", k.seconds_exchange}, {"seconds_build", k.seconds_build},
                        {"seconds_query", k.seconds_query}, {"grid_bytes", k.grid_bytes},
                        {"peak_rss_bytes", k.peak_rss_bytes}});
  }
  // The slowest rank sets each phase's time.
  j["seconds_read"] = read;
  j["seconds_exchange"] = exch;
  j["seconds_build"] = build;
  j["seconds_query"] = query;
  j["peak_rss_bytes"] = summed_rss(r);
  j["peak_rss_bytes_per_particle"] = rss_per_particle(r);
  j["per_rank"] = per_rank;
  return j.dump(2) + "\n";
}

std::string decomposed_count_text(const DecomposedCount& c) {
  const DecomposedRun& r = c.run;
  const Measurement& m = c.m;
  std::string out = printf_string("n = %llu, d = %d, %s, nu = %.6g, search %s, K = %g; %zu ranks, bricks",
                           static_cast<unsigned long long>(r.n), r.d, to_string(r.boundary), r.packing_fraction,
                           to_string(m.search), m.K, r.ranks.size());
  for (std::size_t a = 0; a < r.bricks.size(); ++a) out += printf_string("%s%d", a ? " x " : " ", r.bricks[a]);
  out += printf_string("\n%5s %12s %12s %14s %10s %10s %10s\n", "rank", "owned", "ghosts", "shell_ghosts", "exchange_s",
                "build_s", "query_s");
  for (const auto& k : r.ranks)
    out += printf_string("%5d %12llu %12llu %14llu %10.4g %10.4g %10.4g\n", k.rank, static_cast<unsigned long long>(k.owned),
                  static_cast<unsigned long long>(k.ghosts), static_cast<unsigned long long>(k.shell_ghosts),
                  k.seconds_exchange, k.seconds_build, k.seconds_query);
  out += printf_string("total: %llu cell accesses, %llu narrow-phase checks (all ranks, ghosts included), %llu contacts, "
                "T/N = %.6g (model, serial grid: %.6g)\n",
                static_cast<unsigned long long>(r.work.cell_accesses),
                static_cast<unsigned long long>(r.work.narrow_phase_checks),
                static_cast<unsigned long long>(r.work.contacts), m.T_over_N, m.model_T_over_N);
  out += printf_string("ghosts: %llu level-aware, %llu with a 2 r_max shell (%.3g x); peak memory %.4g bytes per particle\n",
                static_cast<unsigned long long>(r.ghosts), static_cast<unsigned long long>(r.shell_ghosts),
                shell_over_level_aware(r), rss_per_particle(r));
  return out;
}

}  // namespace hgrid::mpi
