#include "mpi/decomposed.hpp"

#include <sys/resource.h>

#include <chrono>
#include <cstring>
#include <optional>

#include "grid/decomposed_query.hpp"
#include "grid/dispatch.hpp"
#include "io/packing_file.hpp"
#include "mpi/comm.hpp"

namespace hgrid::mpi {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }


/// Where each item goes: item k to rank dest[k], grouped by rank (a
/// counting sort; the order within a rank kept).
class Route {
 public:
  Route(std::span<const int> dest, int ranks) : dest_(dest), counts_(static_cast<std::size_t>(ranks), 0) {
    for (int r : dest) ++counts_[static_cast<std::size_t>(r)];
  }
  const std::vector<std::uint64_t>& counts() const { return counts_; }
  /// item(k) for every k, grouped by destination.
  template <class T, class ItemOf>
  UninitVector<T> gather(ItemOf&& item) const {
    std::vector<std::uint64_t> at(counts_.size(), 0);
    for (std::size_t r = 1; r < counts_.size(); ++r) at[r] = at[r - 1] + counts_[r - 1];
    UninitVector<T> out(dest_.size());
    for (std::size_t k = 0; k < dest_.size(); ++k) out[at[static_cast<std::size_t>(dest_[k])]++] = item(k);
    return out;
  }

 private:
  std::span<const int> dest_;
  std::vector<std::uint64_t> counts_;
};

/// The routed items, with room for `spare` more (the ghosts to come).
template <class T>
UninitVector<T> send(const Route& route, const UninitVector<T>& items, std::size_t spare = 0) {
  return all_to_all(std::span<const T>(items), route.counts(), spare);
}

std::uint64_t peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<std::uint64_t>(u.ru_maxrss) * 1024;  // Linux: kilobytes
}

/// The counters as one list of numbers (scalars, then the per-level lists),
/// to be summed over the ranks.
std::vector<std::uint64_t> flatten(const Counters& c) {
  std::vector<std::uint64_t> v{c.cell_accesses, c.narrow_phase_checks, c.contacts, c.occupied_cells, c.searches,
                               c.rows,          c.scanned,             c.probes,   c.list_checks,    c.runs};
  for (const auto* list : {&c.particles_per_level, &c.accesses_by_level, &c.checks_by_level, &c.occupied_by_level,
                           &c.searches_by_level, &c.rows_by_level})
    v.insert(v.end(), list->begin(), list->end());
  return v;
}

void unflatten(const std::vector<std::uint64_t>& v, Counters& c) {
  std::size_t k = 0;
  for (auto* x : {&c.cell_accesses, &c.narrow_phase_checks, &c.contacts, &c.occupied_cells, &c.searches, &c.rows,
                  &c.scanned, &c.probes, &c.list_checks, &c.runs})
    *x = v[k++];
  for (auto* list : {&c.particles_per_level, &c.accesses_by_level, &c.checks_by_level, &c.occupied_by_level,
                     &c.searches_by_level, &c.rows_by_level})
    for (auto& x : *list) x = v[k++];
}

template <int D, Boundary B>
DecomposedRun run(Packing part, std::uint64_t first, std::uint64_t total, double seconds_read,
                  const GridParams& g, bool counted, std::vector<std::pair<std::uint64_t, std::uint64_t>>* pairs_out) {
  const int P = size(), me = rank();
  DecomposedRun out;
  out.d = D;
  out.boundary = B;
  out.n = total;
  for (int a = 0; a < D; ++a) out.box[a] = part.box[a];
  const Extent<D> box = part.extent<D>();
  const Bricks<D> bricks(box, P, B);
  out.bricks.assign(bricks.dims().begin(), bricks.dims().end());
  RankReport rep;
  rep.rank = me;
  rep.seconds_read = seconds_read;

  // What the ranks' parts hold: the largest radius, the particles' volume,
  // the halo volumes, and a sample of radii for the model on rank 0.
  const double longest = longest_side(bricks);
  double r_max = 0;
  std::vector<double> sums(2, 0.0);  // particle volume, sum of halo volumes
  const std::uint64_t stride = std::max<std::uint64_t>(1, (total + kRadiiSample - 1) / kRadiiSample);
  std::vector<double> sample;
  for (std::size_t k = 0; k < part.size(); ++k) {
    const double r = part.radii[k];
    r_max = std::max(r_max, r);
    sums[0] += ball_volume(D, r);
    sums[1] += bricks.halo_volume(ghost_reach(r, longest));
    if ((first + k) % stride == 0) sample.push_back(r);
  }
  r_max = max(r_max);
  out.r_max = r_max;
  sum(sums);
  double box_volume = 1;
  for (double side : box) box_volume *= side;
  out.packing_fraction = sums[0] / box_volume;
  out.halo_volume = total ? sums[1] / static_cast<double>(total) : 0.0;
  out.halo_volume_shell = bricks.halo_volume(ghost_reach(r_max, longest));
  {
    std::vector<std::uint64_t> counts(static_cast<std::size_t>(P), 0);
    counts[0] = sample.size();
    const auto got = all_to_all(std::span<const double>(sample), counts);
    out.radii_sample.assign(got.begin(), got.end());
  }

  // Every particle to the owner of its brick (timed from when every rank
  // has read its part: a slow read is not counted as exchange).
  barrier();
  auto t0 = Clock::now();
  UninitVector<Sphere<D>> spheres;
  UninitVector<std::uint64_t> ids;
  {
    UninitVector<int> dest(part.size());
    auto sphere = [&](std::size_t k) {
      Sphere<D> s{{}, part.radii[k]};
      for (int a = 0; a < D; ++a) s.x[a] = part.positions[k * D + a];
      return s;
    };
    for (std::size_t k = 0; k < dest.size(); ++k) dest[k] = bricks.owner(sphere(k).x);
    const Route route(dest, P);
    // Room for ghosts: an eighth of the own particles covers bricks much
    // wider than the largest particle (a fuller layer moves the array once).
    const std::size_t spare = part.size() / 8 + 1024;
    spheres = send(route, route.gather<Sphere<D>>(sphere), spare);
    ids = send(route, route.gather<std::uint64_t>([&](std::size_t k) { return first + k; }), spare);
    part = Packing{};
  }
  const std::size_t n_owned = spheres.size();
  // The ghosts: each own particle to the ranks within 2 r of it.
  {
    std::vector<std::uint32_t> which;
    std::vector<int> dest;
    for_each_ghost(bricks, std::span<const Sphere<D>>(spheres), me, [&](std::size_t k, int to) {
      which.push_back(static_cast<std::uint32_t>(k));
      dest.push_back(to);
    });
    const Route route(dest, P);
    const auto ghost_spheres = send(route, route.gather<Sphere<D>>([&](std::size_t k) { return spheres[which[k]]; }));
    const auto ghost_ids = send(route, route.gather<std::uint64_t>([&](std::size_t k) { return ids[which[k]]; }));
    rep.ghosts = ghost_spheres.size();
    spheres.insert(spheres.end(), ghost_spheres.begin(), ghost_spheres.end());
    ids.insert(ids.end(), ghost_ids.begin(), ghost_ids.end());
  }
  rep.seconds_exchange = since(t0);
  rep.owned = n_owned;
  // What one 2 r_max shell would have sent (hgrid count; not timed).
  if (counted)
    rep.shell_ghosts = shell_ghost_count(bricks, std::span<const Sphere<D>>(spheres.data(), n_owned), me, r_max);

  // The search of this brick.
  t0 = Clock::now();
  std::optional<HGrid<D, B>> built;
  // A rejected param (a size below the largest diameter, say) fails every rank.
  collective([&] { built.emplace(std::span<const Sphere<D>>(spheres), box, g); });
  const HGrid<D, B>& grid = *built;
  rep.seconds_build = since(t0);
  rep.grid_bytes = grid.memory_bytes();
  std::vector<std::vector<std::pair<std::uint64_t, std::uint64_t>>> found(
      pairs_out ? static_cast<std::size_t>(resolve_threads(g.threads)) : 0);
  auto collect = [&](int t, std::uint64_t i, std::uint64_t j) { found[static_cast<std::size_t>(t)].emplace_back(i, j); };
  t0 = Clock::now();
  const auto sp = std::span<const Sphere<D>>(spheres);
  const auto id = std::span<const std::uint64_t>(ids);
  const bool top_down = g.search == Search::top_down;
  auto query = [&](auto&& f) {
    if (counted)
      return top_down ? query_reported_pairs<Search::top_down, Counted>(grid, sp, id, n_owned, f, g.threads)
                      : query_reported_pairs<Search::bottom_up, Counted>(grid, sp, id, n_owned, f, g.threads);
    return top_down ? query_reported_pairs<Search::top_down, Uncounted>(grid, sp, id, n_owned, f, g.threads)
                    : query_reported_pairs<Search::bottom_up, Uncounted>(grid, sp, id, n_owned, f, g.threads);
  };
  RankCounts c = pairs_out ? query(collect) : query(CountOnly{});
  rep.seconds_query = since(t0);
  out.sizes = grid.sizes();

  // Sums over the ranks; the pairs and the reports to rank 0.
  c.work.contacts = c.reported;
  std::vector<std::uint64_t> flat = flatten(c.work);
  flat.push_back(rep.ghosts);
  flat.push_back(rep.shell_ghosts);
  sum(flat);
  out.work = c.work;
  unflatten(flat, out.work);
  out.ghosts = flat[flat.size() - 2];
  out.shell_ghosts = flat.back();
  if (pairs_out) {
    struct IdPair {  // std::pair is not trivially copyable
      std::uint64_t i, j;
    };
    std::vector<IdPair> mine;
    for (auto& v : found)
      for (const auto& [i, j] : v) mine.push_back({i, j});
    found = {};
    std::vector<std::uint64_t> counts(static_cast<std::size_t>(P), 0);
    counts[0] = mine.size();
    const auto all = all_to_all(std::span<const IdPair>(mine), counts);
    pairs_out->clear();
    pairs_out->reserve(all.size());
    for (const auto& p : all) pairs_out->emplace_back(p.i, p.j);
  }
  rep.peak_rss_bytes = peak_rss_bytes();
  const std::vector<std::uint64_t> mine_u{rep.owned, rep.ghosts, rep.shell_ghosts, rep.grid_bytes, rep.peak_rss_bytes};
  const std::vector<double> mine_d{rep.seconds_read, rep.seconds_exchange, rep.seconds_build, rep.seconds_query};
  std::string bytes(sizeof(std::uint64_t) * mine_u.size() + sizeof(double) * mine_d.size(), '\0');
  std::memcpy(bytes.data(), mine_u.data(), sizeof(std::uint64_t) * mine_u.size());
  std::memcpy(bytes.data() + sizeof(std::uint64_t) * mine_u.size(), mine_d.data(), sizeof(double) * mine_d.size());
  const std::vector<std::string> all = gather(bytes, 0);
  for (std::size_t r = 0; r < all.size(); ++r) {
    std::uint64_t u[5];
    double d[4];
    std::memcpy(u, all[r].data(), sizeof u);
    std::memcpy(d, all[r].data() + sizeof u, sizeof d);
    out.ranks.push_back(RankReport{static_cast<int>(r), u[0], u[1], u[2], d[0], d[1], d[2], d[3], u[3], u[4]});
  }
  return out;
}

}  // namespace

DecomposedRun decomposed_search(const std::string& file, const GridParams& g, bool counted,
                                std::vector<std::pair<std::uint64_t, std::uint64_t>>* pairs_on_root) {
  Packing part;
  std::uint64_t first = 0, total = 0;
  const auto t0 = Clock::now();
  // A file one rank cannot read fails every rank, reported once.
  collective([&] {
    part = read_packing_part(file, static_cast<std::uint64_t>(rank()), static_cast<std::uint64_t>(size()), first,
                             total);
  });
  const double seconds_read = since(t0);
  DecomposedRun out;
  dispatch(part.d, part.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    constexpr Boundary B = decltype(bnd)::value;
    out = run<D, B>(std::move(part), first, total, seconds_read, g, counted, pairs_on_root);
  });
  return out;
}

}  // namespace hgrid::mpi
