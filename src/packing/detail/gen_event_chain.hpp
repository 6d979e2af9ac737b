// Event-chain Monte Carlo for hard spheres (Bernard, Krauth & Wilson,
// Phys. Rev. E 80, 056704 (2009)): one sphere moves straight along +x, +y or
// +z until it meets another, which then moves on in the same direction (the
// "lifting"), until the chain has moved its spheres through a set total
// length. No move is rejected. Chains in a fixed set of directions keep the
// uniform distribution of non-overlapping configurations stationary by
// global balance, not detailed balance (Michel, Kapfer & Krauth, J. Chem.
// Phys. 140, 054116 (2014)). Between chains, the Metropolis swaps of
// gen_equilibrate.hpp exchange two particles' positions (they keep the same
// distribution; Ghimenti, Berthier & van Wijland, arXiv:2402.06585 (2024),
// combine chains and swaps for polydisperse discs).
//
// One thread (a chain may cross the whole box), periodic boxes only (a wall
// cannot be lifted to). The insertion grid finds the first sphere met: for
// each level, the cells of the box swept by the moving sphere's reach, at
// most kEventReach ahead (a longer free flight is taken in steps); ties in
// the distance go to the smaller index, so the chain does not depend on the
// order of the grid's lists, and a run resumed from its positions and
// random state is the uninterrupted one.
#pragma once
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/packing/detail/gen_common.hpp"
#include "hgridlab/packing/detail/gen_equilibrate.hpp"
#include "hgridlab/packing/detail/gen_insert_grid.hpp"

namespace hgrid::detail {

/// Mean total displacement of a chain, in smallest radii (each chain's is
/// drawn uniformly from 0 to twice this: a fixed length can be a multiple
/// of the box side, and a chain then returns its spheres where they were).
inline constexpr double kChainLength = 20.0;
/// How far ahead one event looks, in smallest radii.
inline constexpr double kEventReach = 1.0;
/// Events of a free flight decided by one scan of the grid (a scan that
/// long costs about two of one event; docs/record/PERFORMANCE.md round 25).
inline constexpr double kFlightEvents = 8.0;
/// The scans reach this much further (relative), against rounding in the
/// positions of the events they serve.
inline constexpr double kScanMargin = 1e-9;
/// A moving sphere stops this far short of contact (relative to the contact
/// distance r_i + r_j), far above rounding, so that no move can overlap.
inline constexpr double kContactBackoff = 1e-12;

struct ChainTally {
  std::uint64_t events = 0, lifts = 0, swaps = 0, swapped = 0;
};

template <int D>
class EventChain {
 public:
  static constexpr Boundary B = Boundary::periodic;
  using Vec = std::array<double, D>;

  EventChain(const Extent<D>& box, const std::vector<double>& radii, std::vector<double>& pos,
             double chain_length = kChainLength)
      : box_(box), radii_(radii), pos_(pos), grid_(box, shrunk(radii)) {
    double r0 = radii.empty() ? 1.0 : radii[0];
    for (double r : radii) r0 = std::min(r0, r);
    reach_ = kEventReach * r0;
    chain_ = chain_length * r0;
    const std::size_t n = radii.size();
    level_.resize(n);
    for (std::size_t i = 0; i < n; ++i) level_[i] = grid_.level_of(radii[i] * (1 - kChainShrink));
    node_of_.assign(n, 0);
    particle_of_.assign(n, 0);
    file();
    // The chains keep the shrunk spheres apart: they need a start without
    // overlap (else a chain can be passed on for ever without moving).
    for (std::size_t i = 0; i < n; ++i) {
      const auto id = static_cast<std::uint32_t>(i);
      if (grid_.overlaps(grid_.position(id), grid_.radius(id), 0, id))
        throw InputError("moves", "'event-chain' needs a packing whose pairs overlap by less than " +
                                      std::to_string(kChainShrink) + " of their contact distance");
    }
  }

  /// One sweep: chains until N (1 - kSwapFraction) events, then N
  /// kSwapFraction swap trials (N the number of particles), as the
  /// Metropolis sweep's N trials; positions written back to pos.
  ChainTally sweep(GenRng& rng) {
    ChainTally t;
    const std::size_t n = radii_.size();
    file();
    const auto swaps = static_cast<std::uint64_t>(std::llround(kSwapFraction * static_cast<double>(n)));
    const std::uint64_t events = n - swaps;
    while (t.events < events) {
      const auto a = static_cast<std::uint32_t>(rng.bits() % n);
      const int k = static_cast<int>(rng.bits() % D);
      chain(node_of_[a], k, 2 * rng.uniform() * chain_, t);
    }
    for (std::uint64_t m = 0; m < swaps; ++m) {
      const auto i = static_cast<std::uint32_t>(rng.bits() % n);
      const auto j = static_cast<std::uint32_t>(rng.bits() % n);
      ++t.swaps;
      if (i != j && try_swap(node_of_[i], node_of_[j])) ++t.swapped;
    }
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < D; ++k) pos_[i * D + k] = grid_.position(node_of_[i])[k];
    return t;
  }

 private:
  static std::vector<double> shrunk(std::vector<double> r) {
    for (double& v : r) v *= 1 - kChainShrink;
    return r;
  }

  /// Files the particles (positions from pos) in the grid under nodes
  /// numbered in the order of their cells (a counting sort), so that a
  /// scan's spheres lie near each other in memory. The chains decide by
  /// geometry and particle index alone, so the numbering changes nothing.
  void file() {
    const std::size_t n = radii_.size();
    grid_.rank_by_cell(n, [&](std::size_t i) { return at(i); }, level_, node_of_);
    grid_.reset(Extent<D>{});
    for (std::size_t i = 0; i < n; ++i) particle_of_[node_of_[i]] = static_cast<std::uint32_t>(i);
    for (std::size_t node = 0; node < n; ++node) {
      const std::uint32_t i = particle_of_[node];
      grid_.insert(static_cast<std::uint32_t>(node), at(i), radii_[i] * (1 - kChainShrink), level_[i]);
    }
  }

  Vec at(std::size_t i) const {
    Vec x;
    for (int k = 0; k < D; ++k) x[k] = pos_[i * D + k];
    return x;
  }

  /// One chain from sphere a along +e_k, of total displacement `length`, in
  /// events of at most kEventReach each. The spheres an event may meet are
  /// those filed in the cells its path can reach; a scan of the grid finds
  /// them for one event, or, once a sphere has flown an event's length
  /// without meeting any, for the next kFlightEvents (at omega = 100, nu =
  /// 0.6 four events in five meet nothing). The events of one scan are
  /// then decided among the spheres it found, as a scan per event would
  /// decide them: the same hits and positions, bit for bit.
  void chain(std::uint32_t a, int k, double length, ChainTally& t) {
    double left = length;
    std::uint64_t events = 0, still = 0;  // still: events in a row that moved nothing
    bool flying = false;                  // a's last event met nothing
    while (left > 0) {
      const double ahead = std::min(left, (flying ? kFlightEvents : 1.0) * reach_);
      scan_path(a, k, ahead);
      Vec x = grid_.position(a);
      const Vec x0 = x;
      double travelled = 0;
      std::uint32_t hit = InsertGrid<D, B>::kEmpty;
      // The first event always fits: ahead >= min(left, reach_).
      for (bool first = true; left > 0 && (first || travelled + std::min(left, reach_) <= ahead); first = false) {
        ++events;
        // Each sphere passed the chain on without moving: a ring of pairs in
        // contact around the box (pairs overlapping by more than kChainShrink).
        if (still > radii_.size())
          throw InputError("moves", "'event-chain' is stuck: pairs overlap by more than " +
                                        std::to_string(kChainShrink) + " of their contact distance");
        const double s = first_hit(x[k], k, std::min(left, reach_), hit);
        still = s > 0 ? 0 : still + 1;
        if (s > 0) x[k] = wrap(x[k] + s, box_[k]);
        travelled += s;
        left -= s;
        if (hit != InsertGrid<D, B>::kEmpty) break;
      }
      if (x != x0) grid_.move(a, x);
      flying = hit == InsertGrid<D, B>::kEmpty;
      if (!flying) {
        a = hit;
        ++t.lifts;
      }
    }
    t.events += events;
  }

  /// A sphere sphere a can meet on its path: it lies across the path
  /// within contact (the part of the contact distance left along the path,
  /// root = sqrt(sig^2 - b^2), b its distance from the path line), so a
  /// meets it where a's coordinate along the path reaches xk - root.
  struct Ahead {
    double xk, root, sig;
    std::uint32_t node;
  };

  /// Fills ahead_ with the spheres sphere a can meet while it moves up to
  /// `ahead` along +e_k: for each level, those filed in the cells of the box
  /// its path reaches, kept if they lie across the path within contact.
  void scan_path(std::uint32_t a, int k, double ahead) {
    ahead_.clear();
    const Vec xa = grid_.position(a);
    const double ra = grid_.radius(a);
    Vec lo, hi;
    for (int l = 0; l < grid_.levels(); ++l) {
      const double rl = grid_.level_rmax(l);
      if (rl == 0) continue;
      const double reach = ra + rl;
      lo.fill(-reach);
      hi.fill(reach);
      lo[k] = 0;
      hi[k] = ahead + reach * (1 + kScanMargin);
      grid_.visit_box_all(l, xa, lo, hi, [&](std::uint32_t q, const Vec& xq, double rq) {
        if (q == a) return;
        // Across the path: the nearest image (the box is at least 4 r_max
        // wide, so only one lies within r_a + r_q); the same all along it.
        double b2 = 0;
        for (int m = 0; m < D; ++m) {
          if (m == k) continue;
          const double dx = min_image(xq[m] - xa[m], box_[m]);
          b2 += dx * dx;
        }
        const double sig = ra + rq;
        const double h2 = sig * sig - b2;
        if (h2 <= 0) return;  // passes beside it
        ahead_.push_back(Ahead{xq[k], std::sqrt(h2), sig, q});
      });
    }
  }

  /// How far the sphere at coordinate xk along the path (the path scan_path
  /// scanned) moves before it meets one of ahead_ (at most seg; hit: the
  /// sphere met, or kEmpty if none within seg). Ties in the distance go to
  /// the smaller particle index.
  double first_hit(double xk, int k, double seg, std::uint32_t& hit) const {
    double best = seg;
    hit = InsertGrid<D, B>::kEmpty;
    for (const Ahead& c : ahead_) {
      // The distance ahead, around the box if need be, so that in a box
      // narrower than 4 r_max + 2 reach a sphere just over half a box ahead
      // is not taken for one behind.
      double dk = c.xk - xk;
      if (dk < 0) dk += box_[k];
      if (dk <= 0) continue;  // level with it: moving on only separates them
      double s = dk - c.root - kContactBackoff * c.sig;
      if (s < 0) s = 0;
      if (s < best || (s == best && hit != InsertGrid<D, B>::kEmpty && particle_of_[c.node] < particle_of_[hit])) {
        best = s;
        hit = c.node;
      }
    }
    return best;
  }

  /// Particles i and j exchange positions if neither then overlaps anything.
  bool try_swap(std::uint32_t i, std::uint32_t j) {
    const Vec xi = grid_.position(i), xj = grid_.position(j);
    const double ri = grid_.radius(i), rj = grid_.radius(j);
    grid_.erase(i);
    grid_.erase(j);
    // The larger one into the smaller one's place is the test: the smaller
    // one in the larger one's place cannot overlap anything, since no pair
    // overlaps between events (the constructor checks the start; chains stop
    // short of contact; swaps keep it so), so every other sphere there is at
    // least its contact distance with the larger radius away.
    const bool ok = ri >= rj ? !grid_.overlaps(xj, ri, 0) : !grid_.overlaps(xi, rj, 0);
    grid_.insert(i, ok ? xj : xi, ri);
    grid_.insert(j, ok ? xi : xj, rj);
    return ok;
  }

  Extent<D> box_;
  const std::vector<double>& radii_;
  std::vector<double>& pos_;
  InsertGrid<D, B> grid_;
  std::vector<int> level_;                             // particle -> grid level
  std::vector<std::uint32_t> node_of_, particle_of_;   // particle <-> grid node
  std::vector<Ahead> ahead_;                           // scan_path's spheres
  double reach_ = 1, chain_ = 20;
};

}  // namespace hgrid::detail
