#include "hgridlab/packing/detail/gen_equilibrate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "hgridlab/base/threads.hpp"
#include "hgridlab/packing/detail/gen_event_chain.hpp"
#include "hgridlab/packing/detail/gen_insert_grid.hpp"
#include "hgridlab/packing/detail/gen_move_lists.hpp"

namespace hgrid::detail {
namespace {

/// A domain's random stream: SplitMix64 (Steele, Lea & Flood, OOPSLA 2014),
/// cheap to seed, so every domain of every sweep gets its own.
class DomainRng {
 public:
  DomainRng(std::uint64_t sweep_seed, std::uint64_t domain) : s_(sweep_seed ^ (domain * 0xd1b54a32d192ed03ull)) {
    bits();
  }
  std::uint64_t bits() {
    std::uint64_t z = (s_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(bits() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t s_;
};

template <int D, Boundary B>
bool inside(const std::array<double, D>& x, double r, const Extent<D>& box) {
  if constexpr (B == Boundary::walls)
    for (int k = 0; k < D; ++k)
      if (x[k] < r || x[k] > box[k] - r) return false;
  return true;
}

struct Tally {
  std::uint64_t accepted = 0, proposed = 0, swapped = 0, swaps = 0;
  Tally& operator+=(const Tally& o) {
    accepted += o.accepted;
    proposed += o.proposed;
    swapped += o.swapped;
    swaps += o.swaps;
    return *this;
  }
};

template <int D, Boundary B>
class Checkerboard {
 public:
  Checkerboard(const Extent<D>& box, const std::vector<double>& radii, std::vector<double>& pos,
               OverlapSearch search)
      : box_(box),
        radii_(radii),
        pos_(pos),
        fitting_(fitting(box, radii)),
        width_(width(box, fitting_)),
        grid_(box, radii, width_, domains(fitting_)),
        use_lists_(search == OverlapSearch::lists),
        lists_(box, kListHalfSkin) {
    const auto nd = domains(fitting_);
    std::size_t total = 1;
    for (int k = 0; k < D; ++k) total *= static_cast<std::size_t>(nd[k]);
    start_.assign(total + 1, 0);
    fill_.assign(total, 0);
    members_.assign(radii.size(), 0);
    slot_of_.assign(radii.size(), 0);
    node_.assign(radii.size(), 0);
    node_of_.assign(radii.size(), 0);
    particle_at_.assign(radii.size(), 0);
    level_.resize(radii.size());
    for (std::size_t i = 0; i < radii.size(); ++i) level_[i] = grid_.level_of(radii[i]);
    dom_.assign(radii.size(), 0);
    for (std::size_t c = 0; c < total; ++c) {
      std::size_t rest = c;
      unsigned colour = 0;
      for (int k = 0; k < D; ++k) {
        colour |= static_cast<unsigned>(rest % static_cast<std::size_t>(nd[k]) % 2) << k;
        rest /= static_cast<std::size_t>(nd[k]);
      }
      by_colour_[colour].push_back(static_cast<std::uint32_t>(c));
    }
  }

  /// One sweep: new origin, then the colours in turn.
  Tally sweep(GenRng& rng, int threads) {
    Extent<D> origin;
    for (int k = 0; k < D; ++k) {
      const double u = rng.uniform() * width_[k];
      if constexpr (B == Boundary::periodic) origin[k] = fitting_[k] == 1 ? 0.0 : u;  // one domain: nothing to shift
      else origin[k] = u - width_[k];
    }
    const std::uint64_t seed = rng.bits();
    origin_ = origin;
    const std::size_t n = radii_.size();
    // On one thread the trials are tested on the move lists (which name
    // nodes): the nodes are numbered afresh with the lists and kept in
    // between (the spheres move little between two numberings), and so are
    // the grid's cells (the domains are found at this sweep's origin all the
    // same). On several the grid alone tests the trials, its cells nested in
    // this sweep's domains, so that a domain's lists are written by its own
    // thread alone (and the move lists would name spheres of other domains
    // of the running colour).
    const bool had_lists = lists_on_;
    lists_on_ = use_lists_ && threads <= 1 && !lists_lose_;
    const bool renumber = !lists_on_ || !had_lists || lists_.unlisted() > n / kRelistUnlistedShare ||
                          lists_.relisted() > kRelistPerSphere * n;
    if (renumber) grid_.reset(origin);
    std::fill(start_.begin(), start_.end(), 0);
    for (std::size_t i = 0; i < n; ++i) {
      dom_[i] = grid_.domain_at(at(i), level_[i], origin_);
      ++start_[dom_[i] + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    std::copy(start_.begin(), start_.end() - 1, fill_.begin());
    // A trial draws a slot: a particle's place in the domains' lists (by
    // domain, then by i). Slot start_[c] + k is the k-th particle of domain
    // c, as it was when the grid stored particles by index and then by slot:
    // the trials and their outcomes are unchanged.
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t slot = fill_[dom_[i]]++;
      members_[slot] = static_cast<std::uint32_t>(i);
      slot_of_[i] = static_cast<std::uint32_t>(slot);
    }
    // The grid stores a particle under its node: its rank in the order of
    // the cells it is filed under (a counting sort), so the spheres a scan
    // meets lie near each other in memory. Nodes only place the spheres in
    // memory: which spheres a test meets, and so every outcome, is the same.
    if (renumber) {
      grid_.rank_by_cell(n, [&](std::size_t i) { return at(i); }, level_, node_of_);
      for (std::size_t i = 0; i < n; ++i) particle_at_[node_of_[i]] = static_cast<std::uint32_t>(i);
      for (std::size_t nd = 0; nd < n; ++nd) {
        const std::uint32_t i = particle_at_[nd];
        grid_.insert(static_cast<std::uint32_t>(nd), at(i), radii_[i], level_[i]);
      }
    }
    for (std::size_t slot = 0; slot < n; ++slot) node_[slot] = node_of_[members_[slot]];
    if (lists_on_ && renumber) lists_.build(grid_, n, threads);
    const std::size_t relisted_before = lists_.relisted();
    update_suspects(threads);
    // The tallies are integer sums: the same in any order.
    std::uint64_t accepted = 0, proposed = 0, swapped = 0, swaps = 0;
    for (const auto& list : by_colour_) {
      const auto m_end = static_cast<std::int64_t>(list.size());
#if defined(_OPENMP)
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) reduction(+ : accepted, proposed, swapped, swaps) if (threads > 1)
#endif
      for (std::int64_t m = 0; m < m_end; ++m) {
        const Tally d = run_domain(list[static_cast<std::size_t>(m)], seed);
        accepted += d.accepted;
        proposed += d.proposed;
        swapped += d.swapped;
        swaps += d.swaps;
      }
    }
    (void)threads;
    // Spheres that move far between sweeps (loose packings) are relisted
    // more often than their lists save: then the grid alone, for the run.
    if (lists_on_ && lists_.relisted() - relisted_before > n / kRelistsWorthLists) lists_lose_ = true;
    for (std::size_t slot = 0; slot < n; ++slot)
      for (int k = 0; k < D; ++k) pos_[members_[slot] * D + k] = grid_.position(node_[slot])[k];
    return Tally{accepted, proposed, swapped, swaps};
  }

 private:
  static Extent<D> width(const Extent<D>& box, const std::array<std::int64_t, D>& nd) {
    Extent<D> w;
    for (int k = 0; k < D; ++k) w[k] = box[k] / static_cast<double>(nd[k]);
    return w;
  }
  /// Domains of at least (1 + margin) largest diameters that tile the box;
  /// periodic: an even number when more than 2 (the colours alternate
  /// across the wrap).
  static std::array<std::int64_t, D> fitting(const Extent<D>& box, const std::vector<double>& radii) {
    const double dmax = 2 * *std::max_element(radii.begin(), radii.end()) * (1 + kDomainMargin);
    std::array<std::int64_t, D> nd;
    for (int k = 0; k < D; ++k) {
      nd[k] = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(box[k] / dmax)));
      if (B == Boundary::periodic && nd[k] > 2 && nd[k] % 2) --nd[k];
    }
    return nd;
  }
  /// Domains of the grid: with walls one more per axis (the shifted grid
  /// covers the box from origin - width).
  static std::array<std::int64_t, D> domains(std::array<std::int64_t, D> nd) {
    if constexpr (B == Boundary::walls)
      for (auto& v : nd) ++v;
    return nd;
  }

  std::array<double, D> at(std::size_t i) const {
    std::array<double, D> x;
    for (int k = 0; k < D; ++k) x[k] = pos_[i * D + k];
    return x;
  }

  /// Marks the particles that may overlap another one. A packing made by
  /// growth + FIRE keeps overlaps up to kFinalOverlapTol; Monte Carlo creates
  /// none and only removes them, so "overlaps nothing" stays true once true.
  /// The first sweep tests every particle, later ones only the marked.
  void update_suspects(int threads) {
    const std::size_t n = radii_.size();
    if (!suspects_known_) {
      suspect_.assign(n, 0);
      const auto n_end = static_cast<std::int64_t>(n);
#if defined(_OPENMP)
#pragma omp parallel for num_threads(threads) schedule(static) if (threads > 1)
#endif
      for (std::int64_t s = 0; s < n_end; ++s) {
        const std::uint32_t nd = node_[static_cast<std::size_t>(s)];
        suspect_[members_[static_cast<std::size_t>(s)]] = grid_.overlaps(grid_.position(nd), grid_.radius(nd), 0, nd) ? 1 : 0;
      }
      (void)threads;
      for (std::size_t p = 0; p < n; ++p)
        if (suspect_[p]) suspects_.push_back(static_cast<std::uint32_t>(p));
      suspects_known_ = true;
      return;
    }
    std::size_t kept = 0;
    for (const std::uint32_t p : suspects_) {
      const std::uint32_t nd = node_[slot_of_[p]];
      if (grid_.overlaps(grid_.position(nd), grid_.radius(nd), 0, nd)) suspects_[kept++] = p;
      else suspect_[p] = 0;
    }
    suspects_.resize(kept);
  }

  /// The particles in slots i and j (both of domain c) exchange positions if
  /// neither then overlaps anything nor leaves c (the two cannot overlap each
  /// other). The smaller one needs no test where the larger overlapped
  /// nothing: every distance there is at least r_large + r_k (in floating
  /// point too: the sums and squares round monotonically, and dist2 is
  /// symmetric), so the outcome is the full test's.
  bool try_swap(std::uint32_t si, std::uint32_t sj, std::size_t c) {
    const std::uint32_t i = node_[si], j = node_[sj];
    const std::array<double, D> xi = grid_.position(i), xj = grid_.position(j);
    const double ri = grid_.radius(i), rj = grid_.radius(j);
    if (!inside<D, B>(xj, ri, box_) || !inside<D, B>(xi, rj, box_)) return false;
    if (grid_.domain_at(xj, grid_.level(i), origin_) != c || grid_.domain_at(xi, grid_.level(j), origin_) != c) return false;
    const bool i_fits = ri <= rj && !suspect_[members_[sj]];
    const bool j_fits = rj <= ri && !suspect_[members_[si]];
    // With the move lists on, two spheres of one level keep their nodes and
    // places and exchange radii (and particles), so that both lists stay
    // valid within their budgets; otherwise the nodes exchange places.
    const bool keep_nodes = lists_on_ && grid_.level(i) == grid_.level(j);
    bool ok;
    // Sphere i in j's place is tested on j's move list (skipping i), where
    // that is exact, and so is j in i's place; else both on the grid.
    // (The grid's levels above the listed ones hold neither: j's place is
    // tested on j's list only when j is of a listed level.)
    const bool i_listed = i_fits || (listed(j) && lists_.covers(j, xj, ri));
    const bool j_listed = j_fits || (listed(i) && lists_.covers(i, xi, rj));
    if (i_listed && j_listed) {
      const int above = lists_.levels();
      ok = (i_fits || !(lists_.overlaps(grid_, j, xj, ri, i) || grid_.overlaps(xj, ri, above, i))) &&
           (j_fits || !(lists_.overlaps(grid_, i, xi, rj, j) || grid_.overlaps(xi, rj, above, j)));
      if (ok && !keep_nodes) {
        grid_.erase(i);
        grid_.erase(j);
      }
    } else {
      grid_.erase(i);
      grid_.erase(j);
      ok = (i_fits || !grid_.overlaps(xj, ri, 0)) && (j_fits || !grid_.overlaps(xi, rj, 0));
      if (!ok || keep_nodes) {
        grid_.insert(i, xi, ri);
        grid_.insert(j, xj, rj);
      }
    }
    if (!ok) return false;
    if (keep_nodes) {
      grid_.set_radius(i, rj);
      grid_.set_radius(j, ri);
      std::swap(node_[si], node_[sj]);
      std::swap(node_of_[members_[si]], node_of_[members_[sj]]);
      particle_at_[i] = members_[sj];
      particle_at_[j] = members_[si];
    } else {
      grid_.insert(i, xj, ri);
      grid_.insert(j, xi, rj);
    }
    return true;
  }

  /// Node a relisted if it has moved (or grown) beyond its list budget.
  void relist_if_escaped(std::uint32_t a) {
    if (listed(a) && !lists_.within(a, grid_.position(a), grid_.radius(a))) lists_.relist(grid_, a);
  }

  /// Whether node i (radius r) at x would overlap another sphere: on its
  /// move list and the grid's levels above the listed ones where that is
  /// exact, else on the grid.
  bool move_overlaps(std::uint32_t i, const std::array<double, D>& x, double r) const {
    if (listed(i) && lists_.covers(i, x, r))
      return lists_.overlaps(grid_, i, x, r) || grid_.overlaps(x, r, lists_.levels(), i);
    return grid_.overlaps(x, r, 0, i);
  }

  /// Whether the move lists are on and hold node a's level.
  bool listed(std::uint32_t a) const { return lists_on_ && grid_.level(a) < lists_.levels(); }

  Tally run_domain(std::uint32_t c, std::uint64_t seed) {
    Tally t;
    const auto first = static_cast<std::uint32_t>(start_[c]);
    const std::uint64_t count = start_[c + 1] - start_[c];
    if (count == 0) return t;
    DomainRng rng(seed, c);
    for (std::uint64_t m = 0; m < count; ++m) {
      const std::uint32_t si = first + static_cast<std::uint32_t>(rng.bits() % count);  // a slot
      if (rng.uniform() < kSwapFraction) {
        const std::uint32_t sj = first + static_cast<std::uint32_t>(rng.bits() % count);
        ++t.swaps;
        if (sj != si && try_swap(si, sj, c)) {
          ++t.swapped;
          relist_if_escaped(node_[si]);
          relist_if_escaped(node_[sj]);
        }
        continue;
      }
      const std::uint32_t i = node_[si];
      const double r = grid_.radius(i);
      std::array<double, D> x = grid_.position(i);
      for (int k = 0; k < D; ++k) {
        x[k] += (2 * rng.uniform() - 1) * kMcStep * r;
        if constexpr (B == Boundary::periodic) x[k] = wrap(x[k], box_[k]);
      }
      ++t.proposed;
      if (!inside<D, B>(x, r, box_) || grid_.domain_at(x, grid_.level(i), origin_) != c || move_overlaps(i, x, r))
        continue;
      grid_.move(i, x);
      ++t.accepted;
      relist_if_escaped(i);
    }
    return t;
  }

  Extent<D> box_;
  const std::vector<double>& radii_;
  std::vector<double>& pos_;
  std::array<std::int64_t, D> fitting_;  // domains that tile the box, per axis
  Extent<D> width_;                       // their width
  InsertGrid<D, B> grid_;
  std::array<std::vector<std::uint32_t>, (1u << D)> by_colour_;
  std::vector<std::size_t> start_, fill_, dom_;
  std::vector<std::uint32_t> members_;  // slot -> particle
  std::vector<std::uint32_t> slot_of_;  // particle -> slot
  std::vector<std::uint32_t> node_;         // slot -> grid node
  std::vector<std::uint32_t> node_of_;      // particle -> grid node (rank_by_cell)
  std::vector<std::uint32_t> particle_at_;  // grid node -> particle
  std::vector<int> level_;  // particle -> its grid level
  // Particles that may overlap another (a superset; see update_suspects).
  std::vector<char> suspect_;
  std::vector<std::uint32_t> suspects_;
  bool suspects_known_ = false;
  // The move lists (gen_move_lists.hpp): asked for; on (one thread).
  bool use_lists_;
  bool lists_on_ = false, lists_lose_ = false;
  Extent<D> origin_{};  // this sweep's domains start here
  MoveLists<D, B> lists_;
};

template <class Sweeper>
void sweeps(Sweeper& board, std::uint64_t target, int T, GenRng& rng, Progress& progress, Equilibration& e,
            const EquilibrationCheckpoint& checkpoint, double checkpoint_seconds, const EquilibrationObserver& observe) {
  const std::uint64_t first = e.sweeps;
  double saved = progress.elapsed();
  while (e.sweeps < target) {
    const Tally t = board.sweep(rng, T);
    e.moves_accepted += t.accepted;
    e.moves_proposed += t.proposed;
    e.swaps_accepted += t.swapped;
    e.swaps_proposed += t.swaps;
    ++e.sweeps;
    std::string extra;
    const bool done = observe && observe(e, extra);
    char buf[96];
    std::snprintf(buf, sizeof buf, "sweep %llu, acceptance %.2f (moves), %.2f (swaps)",
                  static_cast<unsigned long long>(e.sweeps), e.displacement_acceptance(), e.swap_acceptance());
    progress.update(static_cast<double>(e.sweeps - first) / static_cast<double>(target - first), buf + extra);
    if (done) break;
    if (checkpoint && e.sweeps < target && progress.elapsed() - saved >= checkpoint_seconds) {
      checkpoint(e);
      saved = progress.elapsed();
    }
  }
}


/// The event chains' sweeps as the checkerboard's: an event counts as an
/// accepted move.
template <int D>
class Chains {
 public:
  Chains(const Extent<D>& box, const std::vector<double>& radii, std::vector<double>& pos) : ec_(box, radii, pos) {}
  Tally sweep(GenRng& rng, int) {
    const ChainTally c = ec_.sweep(rng);
    return Tally{c.events, c.events, c.swapped, c.swaps};
  }

 private:
  EventChain<D> ec_;
};

template <int D, Boundary B>
void run(bool event_chain, const std::array<double, 3>& box3, const std::vector<double>& radii,
         std::vector<double>& pos, std::uint64_t target, int threads, GenRng& rng, Progress& progress,
         Equilibration& e, const EquilibrationCheckpoint& checkpoint, double checkpoint_seconds,
         const EquilibrationObserver& observe, OverlapSearch search) {
  Extent<D> box;
  for (int k = 0; k < D; ++k) box[k] = box3[k];
  if constexpr (B == Boundary::periodic)
    if (event_chain) {
      Chains<D> chains(box, radii, pos);
      sweeps(chains, target, 1, rng, progress, e, checkpoint, checkpoint_seconds, observe);
      return;
    }
  Checkerboard<D, B> board(box, radii, pos, search);
  sweeps(board, target, resolve_threads(threads), rng, progress, e, checkpoint, checkpoint_seconds, observe);
}

}  // namespace

void equilibrate(int d, Boundary b, bool event_chain, const std::array<double, 3>& box, const std::vector<double>& radii,
                 std::vector<double>& pos, std::uint64_t target, int threads, GenRng& rng, Progress& progress,
                 Equilibration& e, const EquilibrationCheckpoint& checkpoint, double checkpoint_seconds,
                 const EquilibrationObserver& observe, OverlapSearch search) {
  const auto go = [&](auto run_one) {
    run_one(event_chain, box, radii, pos, target, threads, rng, progress, e, checkpoint, checkpoint_seconds, observe,
            search);
  };
  if (d == 2) {
    if (b == Boundary::walls) go(run<2, Boundary::walls>);
    else go(run<2, Boundary::periodic>);
  } else if (b == Boundary::walls) {
    go(run<3, Boundary::walls>);
  } else {
    go(run<3, Boundary::periodic>);
  }
}

}  // namespace hgrid::detail
