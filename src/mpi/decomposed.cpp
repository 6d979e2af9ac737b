#include "hgridlab/mpi/decomposed.hpp"

#include <sys/resource.h>

#include <cstring>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "hgridlab/base/clock.hpp"
#include "hgridlab/domain/decomposed_query.hpp"
#include "hgridlab/grid/dispatch.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/mpi/comm.hpp"

namespace hgrid::mpi {
namespace {

/// Where the particles read here go, in one all-to-all: particle k to its
/// owner owner[k] as an own particle, and particle ghost_k[g] to rank
/// ghost_to[g] as a ghost. Every rank receives its own particles first, then
/// its ghosts; what a rank keeps for itself is written in place, not sent.
class Delivery {
 public:
  Delivery(std::span<const int> owner, std::span<const std::size_t> ghost_k, std::span<const int> ghost_to)
      : owner_(owner), ghost_k_(ghost_k), ghost_to_(ghost_to) {
    const std::size_t P = static_cast<std::size_t>(size());
    std::vector<std::uint64_t> own(P, 0), ghosts(P, 0);
    for (int r : owner) ++own[static_cast<std::size_t>(r)];
    for (int r : ghost_to) ++ghosts[static_cast<std::size_t>(r)];
    for (auto* v : {&own, &ghosts}) {
      sent_.push_back(*v);
      got_.push_back(detail::exchange_counts(*v));
    }
    for (auto c : got_[0]) n_owned_ += c;
    for (auto c : got_[1]) n_ghosts_ += c;
  }
  std::size_t owned() const { return n_owned_; }
  std::size_t ghosts() const { return n_ghosts_; }

  /// item(k) of every particle k read here, delivered: this rank's own
  /// particles (owned() of them, in rank order of the senders), then its
  /// ghosts.
  template <class T, class ItemOf>
  UninitVector<T> deliver(ItemOf&& item) const {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::size_t P = static_cast<std::size_t>(size()), me = static_cast<std::size_t>(rank());
    UninitVector<T> out(n_owned_ + n_ghosts_);
    // Per kind (own, ghost): where each rank's items start in the send
    // buffer and in `out`; this rank's own items go straight into `out`.
    std::vector<std::uint64_t> send_at[2], recv_at[2], send_counts[2], recv_counts[2];
    std::uint64_t sent = 0;
    std::vector<T*> cursor[2];
    for (int kind = 0; kind < 2; ++kind) {
      send_at[kind].assign(P, 0), recv_at[kind].assign(P, 0);
      send_counts[kind] = sent_[kind], recv_counts[kind] = got_[kind];
      send_counts[kind][me] = recv_counts[kind][me] = 0;
      std::uint64_t at = kind == 0 ? 0 : n_owned_;
      for (std::size_t r = 0; r < P; ++r) recv_at[kind][r] = at, at += got_[kind][r];
    }
    for (std::size_t r = 0; r < P; ++r)
      for (int kind = 0; kind < 2; ++kind) send_at[kind][r] = sent, sent += send_counts[kind][r];
    UninitVector<T> buffer(sent);
    for (int kind = 0; kind < 2; ++kind) {
      cursor[kind].resize(P);
      for (std::size_t r = 0; r < P; ++r)
        cursor[kind][r] = r == me ? out.data() + recv_at[kind][r] : buffer.data() + send_at[kind][r];
    }
    for (std::size_t k = 0; k < owner_.size(); ++k) *cursor[0][static_cast<std::size_t>(owner_[k])]++ = item(k);
    for (std::size_t g = 0; g < ghost_k_.size(); ++g)
      *cursor[1][static_cast<std::size_t>(ghost_to_[g])]++ = item(ghost_k_[g]);
    for (int kind = 0; kind < 2; ++kind)
      detail::exchange_items_at(buffer.data(), send_counts[kind], send_at[kind], out.data(), recv_counts[kind],
                        recv_at[kind], sizeof(T));
    return out;
  }

 private:
  std::span<const int> owner_;
  std::span<const std::size_t> ghost_k_;
  std::span<const int> ghost_to_;
  std::vector<std::vector<std::uint64_t>> sent_, got_;  // per kind (own, ghost), per rank
  std::size_t n_owned_ = 0, n_ghosts_ = 0;
};

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

  // Every particle to the owner of its brick and, as a ghost, to the ranks
  // within its reach, decided where it was read (timed from when every
  // rank has read its part: a slow read is not counted as exchange).
  barrier();
  auto t0 = Clock::now();
  UninitVector<Sphere<D>> spheres;
  UninitVector<std::uint64_t> ids;
  std::size_t n_owned = 0;
  {
    UninitVector<int> owner(part.size());
    std::vector<std::size_t> ghost_k;
    std::vector<int> ghost_to;
    auto sphere = [&](std::size_t k) {
      Sphere<D> s{{}, part.radii[k]};
      for (int a = 0; a < D; ++a) s.x[a] = part.positions[k * D + a];
      return s;
    };
    for (std::size_t k = 0; k < owner.size(); ++k) {
      const Sphere<D> s = sphere(k);
      owner[k] = bricks.place(s.x, ghost_reach(s.r, longest), [&](int to) {
        ghost_k.push_back(k);
        ghost_to.push_back(to);
      });
    }
    const Delivery delivery(owner, ghost_k, ghost_to);
    spheres = delivery.deliver<Sphere<D>>(sphere);
    // Global indices for the pairs' output only (counting needs none).
    if (pairs_out) ids = delivery.deliver<std::uint64_t>([&](std::size_t k) { return first + k; });
    n_owned = delivery.owned();
    rep.ghosts = delivery.ghosts();
    part = Packing{};
  }
  rep.seconds_exchange = seconds_since(t0);
  rep.owned = n_owned;
  // What one 2 r_max shell would have sent (hgrid count; not timed).
  if (counted)
    rep.shell_ghosts = shell_ghost_count(bricks, std::span<const Sphere<D>>(spheres.data(), n_owned), me, r_max);

  // The search of this brick.
  t0 = Clock::now();
  std::optional<HGrid<D, B>> built;
  // A rejected param (a size below the largest diameter, say) fails every rank.
  // (The grid holds the own particles; the ghosts search it afterwards.)
  collective([&] { built.emplace(std::span<const Sphere<D>>(spheres.data(), n_owned), box, g); });
  const HGrid<D, B>& grid = *built;
  rep.seconds_build = seconds_since(t0);
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
      return top_down
                 ? query_reported_pairs<Search::top_down, Counted>(grid, sp, n_owned, bricks, me, id, f, g.threads)
                 : query_reported_pairs<Search::bottom_up, Counted>(grid, sp, n_owned, bricks, me, id, f, g.threads);
    return top_down
               ? query_reported_pairs<Search::top_down, Uncounted>(grid, sp, n_owned, bricks, me, id, f, g.threads)
               : query_reported_pairs<Search::bottom_up, Uncounted>(grid, sp, n_owned, bricks, me, id, f, g.threads);
  };
  RankCounts c = pairs_out ? query(collect) : query(CountOnly{});
  rep.seconds_query = seconds_since(t0);
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
    if (part.tilted())  // its bricks and ghosts are cut along the axes
      throw InputError("box", "the decomposed search cuts orthogonal boxes; " + file +
                                  " has a tilted box (count it without --decompose)");
  });
  const double seconds_read = seconds_since(t0);
  DecomposedRun out;
  dispatch(part.d, part.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    constexpr Boundary B = decltype(bnd)::value;
    out = run<D, B>(std::move(part), first, total, seconds_read, g, counted, pairs_on_root);
  });
  return out;
}

}  // namespace hgrid::mpi
