// hgrid pairs|count FILE --sizes ... --decompose: the search split over the
// ranks of an MPI run (mpi/decomposed.hpp); rank 0 prints.
#include <malloc.h>

#include <climits>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "common.hpp"
#include "hgridlab/model/distribution.hpp"
#include "hgridlab/measure/fields.hpp"
#include "hgridlab/measure/measurement.hpp"
#include "hgridlab/model/model.hpp"
#include "hgridlab/mpi/comm.hpp"
#include "hgridlab/mpi/decomposed.hpp"

namespace hgrid::cli {

int threads_per_rank(int threads) {
  if (threads != 0 || mpi::size() == 1 || std::getenv("OMP_NUM_THREADS")) return threads;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, cores / mpi::local_size());
}

namespace {
/// A rank frees the part of the file it read once it has handed it out, and
/// then builds its grid: with glibc's defaults those arrays go back to the
/// system and the grid's come as fresh pages, each paid for by a page fault
/// on first touch (~0.1 s per rank at N = 10^7 on 2 ranks, a quarter of the
/// build). Kept in the heap instead, they are reused. One search per
/// process, so holding on to freed memory costs nothing after it.
void keep_freed_memory() {
#ifdef M_MMAP_MAX
  mallopt(M_MMAP_MAX, 0);                      // large blocks from the heap too
  mallopt(M_TRIM_THRESHOLD, INT_MAX);         // not handed back (below 2 GB)
#endif
}
}  // namespace

void run_decomposed_pairs(const std::string& file, const GridParams& g) {
  keep_freed_memory();
  std::vector<std::pair<std::uint64_t, std::uint64_t>> pairs;
  mpi::decomposed_search(file, g, false, &pairs);
  if (mpi::rank() != 0) return;
  PairWriter out;
  for (const auto& [i, j] : pairs) out(i, j);
}

void run_decomposed_count(const std::string& file, const GridParams& g, double K, bool as_json) {
  keep_freed_memory();
  const mpi::DecomposedRun r = mpi::decomposed_search(file, g, true, nullptr);
  if (mpi::rank() != 0) return;
  // The record of the serial search's fields, for the work of every rank
  // (ghosts' searches included: what decomposing costs) and the model of
  // the serial grid for a sample of the radii.
  Measurement m;
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
  const double n = static_cast<double>(r.n);
  const ModelResult model = evaluate_model(Empirical(r.radii_sample),
                                           ModelParams{r.d, r.packing_fraction, K, g.search}, r.sizes);
  m.model_T_over_N = model.T_over_N;
  m.model_T_cd_over_N = model.T_cd_over_N;
  m.model_T_ca_over_N = model.T_ca_over_N;
  static constexpr std::string_view kFields[] = {
      "n", "d", "boundary", "nu_achieved", "search", "threads", "K", "sizes_requested", "sizes", "levels",
      "cell_accesses", "narrow_phase_checks", "contacts", "T_over_N", "T_cd_over_N", "T_ca_over_N",
      "model_T_over_N", "model_T_cd_over_N", "model_T_ca_over_N"};
  using json = nlohmann::ordered_json;
  json j = json::parse(measurement_json(m, kFields));
  j["box"] = std::vector<double>(r.box.begin(), r.box.begin() + r.d);
  j["r_max"] = r.r_max;
  j["ranks"] = r.ranks.size();
  j["bricks"] = r.bricks;
  j["model_radii"] = r.radii_sample.size();
  j["ghosts"] = r.ghosts;
  j["shell_ghosts"] = r.shell_ghosts;
  j["shell_over_level_aware"] = r.ghosts ? static_cast<double>(r.shell_ghosts) / static_cast<double>(r.ghosts) : 0.0;
  j["halo_volume"] = r.halo_volume;
  j["halo_volume_shell"] = r.halo_volume_shell;
  double read = 0, exch = 0, build = 0, query = 0;
  std::uint64_t rss = 0;
  json per_rank = json::array();
  for (const auto& k : r.ranks) {
    read = std::max(read, k.seconds_read), exch = std::max(exch, k.seconds_exchange);
    build = std::max(build, k.seconds_build), query = std::max(query, k.seconds_query);
    rss += k.peak_rss_bytes;
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
  j["peak_rss_bytes"] = rss;
  j["peak_rss_bytes_per_particle"] = n > 0 ? static_cast<double>(rss) / n : 0.0;
  j["per_rank"] = per_rank;
  if (as_json) {
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::printf("n = %llu, d = %d, %s, nu = %.6g, search %s, K = %g; %zu ranks, bricks", (unsigned long long)r.n, r.d,
              to_string(r.boundary), r.packing_fraction, to_string(g.search), K, r.ranks.size());
  for (std::size_t a = 0; a < r.bricks.size(); ++a) std::printf("%s%d", a ? " x " : " ", r.bricks[a]);
  std::printf("\n%5s %12s %12s %14s %10s %10s %10s\n", "rank", "owned", "ghosts", "shell_ghosts", "exchange_s",
              "build_s", "query_s");
  for (const auto& k : r.ranks)
    std::printf("%5d %12llu %12llu %14llu %10.4g %10.4g %10.4g\n", k.rank, (unsigned long long)k.owned,
                (unsigned long long)k.ghosts, (unsigned long long)k.shell_ghosts, k.seconds_exchange, k.seconds_build,
                k.seconds_query);
  std::printf("total: %llu cell accesses, %llu narrow-phase checks (all ranks, ghosts included), %llu contacts, "
              "T/N = %.6g (model, serial grid: %.6g)\n",
              (unsigned long long)r.work.cell_accesses, (unsigned long long)r.work.narrow_phase_checks,
              (unsigned long long)r.work.contacts, m.T_over_N, m.model_T_over_N);
  std::printf("ghosts: %llu level-aware, %llu with a 2 r_max shell (%.3g x); peak memory %.4g bytes per particle\n",
              (unsigned long long)r.ghosts, (unsigned long long)r.shell_ghosts, j["shell_over_level_aware"].get<double>(),
              j["peak_rss_bytes_per_particle"].get<double>());
}

}  // namespace hgrid::cli
