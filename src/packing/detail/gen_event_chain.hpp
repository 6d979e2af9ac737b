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

  /// One chain from sphere a along +e_k, of total displacement `length`.
  void chain(std::uint32_t a, int k, double length, ChainTally& t) {
    double left = length;
    std::uint64_t events = 0, still = 0;  // still: events in a row that moved nothing
    while (left > 0) {
      ++events;
      // Each sphere passed the chain on without moving: a ring of pairs in
      // contact around the box (pairs overlapping by more than kChainShrink).
      if (still > radii_.size())
        throw InputError("moves", "'event-chain' is stuck: pairs overlap by more than " +
                                      std::to_string(kChainShrink) + " of their contact distance");
      const double seg = std::min(left, reach_);
      std::uint32_t hit = InsertGrid<D, B>::kEmpty;
      const double s = first_hit(a, k, seg, hit);
      still = s > 0 ? 0 : still + 1;
      if (s > 0) {
        Vec x = grid_.position(a);
        x[k] = wrap(x[k] + s, box_[k]);
        grid_.move(a, x);
      }
      left -= s;
      if (hit != InsertGrid<D, B>::kEmpty) {
        a = hit;
        ++t.lifts;
      }
    }
    t.events += events;
  }

  /// How far sphere a moves along +e_k before it meets another (at most
  /// seg; hit: the sphere met, or kEmpty if none within seg).
  double first_hit(std::uint32_t a, int k, double seg, std::uint32_t& hit) const {
    const Vec xa = grid_.position(a);
    const double ra = grid_.radius(a);
    double best = seg;
    Vec lo, hi;
    for (int l = 0; l < grid_.levels(); ++l) {
      const double rl = grid_.level_rmax(l);
      if (rl == 0) continue;
      const double reach = ra + rl;
      lo.fill(-reach);
      hi.fill(reach);
      lo[k] = 0;
      hi[k] = best + reach;
      grid_.visit_box(l, xa, lo, hi, [&](std::uint32_t q, const Vec& xq, double rq) {
        if (q == a) return true;
        // Across the path: the nearest image (the box is at least 4 r_max
        // wide, so only one lies within r_a + r_q). Along it: the distance
        // ahead, around the box if need be, so that in a box narrower than
        // 4 r_max + 2 reach a sphere just over half a box ahead is not taken
        // for one behind.
        double b2 = 0, dk = 0;
        for (int m = 0; m < D; ++m) {
          if (m == k) {
            dk = xq[m] - xa[m];
            if (dk < 0) dk += box_[m];
          } else {
            const double dx = min_image(xq[m] - xa[m], box_[m]);
            b2 += dx * dx;
          }
        }
        if (dk <= 0) return true;  // level with it: moving on only separates them
        const double sig = ra + rq;
        const double h2 = sig * sig - b2;
        if (h2 <= 0) return true;  // passes beside it
        double s = dk - std::sqrt(h2) - kContactBackoff * sig;
        if (s < 0) s = 0;
        if (s < best || (s == best && hit != InsertGrid<D, B>::kEmpty && particle_of_[q] < particle_of_[hit])) {
          best = s;
          hit = q;
        }
        return true;
      });
    }
    return best;
  }

  /// Particles i and j exchange positions if neither then overlaps anything.
  bool try_swap(std::uint32_t i, std::uint32_t j) {
    const Vec xi = grid_.position(i), xj = grid_.position(j);
    const double ri = grid_.radius(i), rj = grid_.radius(j);
    grid_.erase(i);
    grid_.erase(j);
    // The larger one into the smaller one's place first: it fails soonest.
    const bool ok = ri >= rj ? !grid_.overlaps(xj, ri, 0) && !grid_.overlaps(xi, rj, 0)
                             : !grid_.overlaps(xi, rj, 0) && !grid_.overlaps(xj, ri, 0);
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
  double reach_ = 1, chain_ = 20;
};

}  // namespace hgrid::detail
