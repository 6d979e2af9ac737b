// A contact list for time stepping: the HGrid as a simulation's contact
// detection, step after step.
//
// At every update() the list hands over exactly the pairs with distance
// < r_i + r_j (minimum image on periodic axes), tested with the grid's own
// expression (grid/geometry.hpp: dx = x_j - x_i per axis, the minimum image
// where the axis is periodic, s = ((0 + dx0^2) + dx1^2) [+ dx2^2], s <
// (r_i + r_j)^2) on the same wrapped coordinates: the same set, bit for
// bit, as a fresh HGrid of the same spheres. It does not search the grid at
// every step: it keeps the candidate pairs closer than R_i + R_j, each
// radius inflated to R_i = r_i (1 + skin_rel) + skin / 2 when the list was
// built, and tests only those. It is rebuilt (an HGrid of the inflated
// spheres, rebuilt in place) only when a pair could have come into contact
// unseen: when the two smallest margins R_i - r_i(now) - |u_i| (u_i the
// displacement since the build) add up to no more than what the periodic
// sides' changes can shift an image. This is the rule of LAMMPS's
// `neigh_modify check yes` (rebuild when a particle has moved half the
// skin), per particle, with growing radii and a changing box counted, as
// the packing generator's FIRE relaxation has kept it
// (packing/detail/gen_relax.cpp); Cabana keeps its VerletList over its
// LinkedCellList in the same way.
//
// Boundaries per axis (periodic or walled, e.g. a pour's `p p f`), any
// origin, a box whose sides change between steps (set_box). Several
// threads give the same pairs in the same (canonical) order. In steady
// state (same particle count, same number of grid levels) an update
// allocates nothing.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "hgridlab/base/clock.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/base/parallel.hpp"
#include "hgridlab/base/threads.hpp"
#include "hgridlab/contacts/pair_keys.hpp"
#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/grid/hgrid.hpp"
#include "hgridlab/grid/params.hpp"
#include "hgridlab/grid/tilted.hpp"
#include "hgridlab/grid/tilted_box.hpp"
#include "hgridlab/grid/uninit_vector.hpp"

namespace hgrid {

/// A simulation box: sides, lower corner, and the boundary of each axis.
/// A walled axis k holds centres in [origin_k, origin_k + side_k]; a
/// periodic one wraps them into [origin_k, origin_k + side_k).
template <int D>
struct ListBox {
  Extent<D> side{};
  std::array<double, D> origin{};
  std::array<bool, D> periodic{};
  /// A triclinic box (every axis periodic): LAMMPS's lattice, edge vectors
  /// (lx, 0, 0), (xy, ly, 0), (xz, yz, lz) (grid/tilted_box.hpp); a
  /// Lees-Edwards box is its xy, the offset less a multiple of lx. Its tilts
  /// may change at every set_box (a growing shear); fixed at construction.
  bool triclinic = false;
  std::array<double, 3> tilt{};  // xy, xz, yz (2D: xy); used when triclinic
};

/// Cell sizes doubling from the smallest diameter 2 rmin up to the largest
/// 2 rmax (one level if monodisperse): cheap, and within a few tens of per
/// cent of the model's optimum; the default of a contact list and the
/// packing generator's grid.
inline std::vector<double> doubling_sizes(double rmin, double rmax) {
  std::vector<double> s{2 * rmin * (1 + 1e-9)};
  while (s.back() < 2 * rmax) s.push_back(std::min(2 * s.back(), 2 * rmax * (1 + 1e-9)));
  return s;
}

struct ContactListParams {
  /// Cell sizes s_h for the particles' own radii (e.g. the model's optimum
  /// for their size distribution, as for a grid rebuilt every step); the
  /// grid of the inflated spheres uses s_h (1 + skin_rel) + skin, which
  /// puts every sphere on the level its own radius would have. The last must
  /// be at least the largest diameter. Empty: doubling_sizes of the
  /// inflated radii, laid out again when the radii outgrow them.
  std::vector<double> sizes;
  Search search = Search::bottom_up;
  /// Threads of the build, the search and the per-step test (0 = all).
  int threads = 1;
  /// The pair's absolute skin: a pair is a candidate within r_i + r_j + skin
  /// (LAMMPS's `neighbor` skin). >= 0.
  double skin = 0;
  /// Each radius inflated by skin_rel r_i besides (a skin that grows with
  /// the radius, as the packing generator's). >= 0. Both 0: the list is
  /// rebuilt whenever anything moves.
  double skin_rel = 0;
};

/// What a contact list did: counts and seconds since it was made.
struct ContactListStats {
  std::uint64_t steps = 0;           // update() calls
  std::uint64_t builds = 0;          // of them, those that rebuilt the candidates
  std::uint64_t candidates = 0;      // pairs in the list now
  std::uint64_t contacts = 0;        // contacts now
  std::uint64_t candidates_tested = 0;  // summed over the steps
  /// Over the builds that displacements called for (not those of a new
  /// particle count or of the first update): the margin used up when each
  /// came (the two largest displacements' sum, with growth, when skin_rel is
  /// 0; it may exceed the skin when one step moved that far) and the steps
  /// since the build before. travel / travel_steps is how fast the particles
  /// use up a skin, even when the list is rebuilt at every step.
  double travel = 0;
  std::uint64_t travel_steps = 0;
  /// Over the displacement-called builds one step after a build that came
  /// one step after the build before it (a list rebuilt at every step): the
  /// two largest displacements' sum over the last step and over the last
  /// two steps. travel_two / travel_one tells how displacements grow with
  /// time: 2 for straight lines, sqrt(2) for a random walk
  /// (advice/skin_model.hpp).
  double travel_one = 0, travel_two = 0;
  double seconds_check = 0;   // reading the positions, the skin check
  double seconds_build = 0;   // grid build, candidate search, storing the list
  double seconds_grid = 0;    //   of which: the grid build (HGrid::rebuild)
  double seconds_test = 0;    // the per-step test of the candidates
  double seconds() const { return seconds_check + seconds_build + seconds_test; }
  double seconds_per_step() const { return steps ? seconds() / static_cast<double>(steps) : 0.0; }
};

template <int D>
class ContactList {
  static_assert(D == 2 || D == 3, "ContactList supports d = 2 and d = 3");

 public:
  using Vec = std::array<double, D>;
  static constexpr int dimension = D;

  /// Throws InputError naming the field (box, skin, skin_rel, threads).
  ContactList(const ListBox<D>& box, ContactListParams params) : params_(std::move(params)) {
    if (!(std::isfinite(params_.skin) && params_.skin >= 0))
      throw InputError("skin", "must be finite and >= 0 (got " + format_number(params_.skin) + ")");
    if (!(std::isfinite(params_.skin_rel) && params_.skin_rel >= 0))
      throw InputError("skin_rel", "must be finite and >= 0 (got " + format_number(params_.skin_rel) + ")");
    if (params_.threads < 0) throw InputError("threads", "must be >= 0 (0 = all cores)");
    check_box(box);
    box_ = box;
    mask_ = 0;
    for (int k = 0; k < D; ++k) mask_ |= box.periodic[k] ? 1u << k : 0u;
    threads_ = resolve_threads(params_.threads);
    keys_.resize(static_cast<std::size_t>(threads_));
  }

  /// A new box (sides and origin; the axes' boundaries stay as they were):
  /// compression, expansion, a moving wall. Positions handed to the next
  /// update() are read in it. The list is rebuilt only when the periodic
  /// sides have changed by more than the skin covers.
  void set_box(const ListBox<D>& box) {
    check_box(box);
    for (int k = 0; k < D; ++k)
      if (box.periodic[k] != box_.periodic[k])
        throw InputError("box", "axis " + std::to_string(k + 1) + " must stay " +
                                    (box_.periodic[k] ? "periodic" : "walled"));
    if (box.triclinic != box_.triclinic)
      throw InputError("box", box_.triclinic ? "must stay triclinic" : "cannot become triclinic (make the list with triclinic = true)");
    box_ = box;
  }
  const ListBox<D>& box() const { return box_; }

  /// A new skin (a skin tuner's choice), and cell sizes (empty: the
  /// default), used from the next build on; the list stays exact meanwhile
  /// (its margins are those of the radii it was built with). Throws
  /// InputError naming the field, and then changes nothing.
  void set_skin(double skin, double skin_rel = 0) {
    if (!(std::isfinite(skin) && skin >= 0))
      throw InputError("skin", "must be finite and >= 0 (got " + format_number(skin) + ")");
    if (!(std::isfinite(skin_rel) && skin_rel >= 0))
      throw InputError("skin_rel", "must be finite and >= 0 (got " + format_number(skin_rel) + ")");
    params_.skin = skin;
    params_.skin_rel = skin_rel;
  }
  void set_sizes(std::vector<double> sizes) { params_.sizes = std::move(sizes); }

  /// New positions and radii (user coordinates), one sphere per particle in
  /// the same order as the contacts' indices. Returns whether the
  /// candidates were rebuilt. A different count than the last call rebuilds
  /// (particles inserted or removed). Throws InputError naming the particle
  /// and the field (a non-finite coordinate, a radius <= 0, a centre outside
  /// a walled axis, naming the axis), and then leaves the list as it was.
  bool update(std::span<const Sphere<D>> spheres) {
    return update_from(spheres.size(), [&](std::size_t i) { return spheres[i]; });
  }
  /// Same, from n x D positions (row-major) and n radii.
  bool update(std::span<const double> positions, std::span<const double> radii) {
    if (positions.size() != radii.size() * D)
      throw InputError("positions", "must hold " + std::to_string(D) + " coordinates per radius (got " +
                                        std::to_string(positions.size()) + " for " + std::to_string(radii.size()) +
                                        " radii)");
    // The input read 32 particles ahead: the check streams it once, and
    // the hardware's prefetch alone left it waiting (a pour's frame, 2 x
    // 10^4 particles: the check -15 to -25 %).
    const double* const px = positions.data();
    const double* const pr = radii.data();
    const std::size_t last = radii.empty() ? 0 : radii.size() - 1;
    return update_from(radii.size(), [=](std::size_t i) {
      const std::size_t ahead = std::min(i + kReadAhead, last);
      __builtin_prefetch(px + ahead * D);
      __builtin_prefetch(pr + ahead);
      Sphere<D> s;
      for (int k = 0; k < D; ++k) s.x[k] = positions[i * D + k];
      s.r = radii[i];
      return s;
    });
  }

  std::size_t size() const { return s_.size(); }
  /// The contacts as compressed rows: the partners j > i of particle i are
  /// partners()[start()[i]] .. partners()[start()[i + 1] - 1], ascending.
  std::span<const std::uint32_t> start() const { return {start_.data(), start_.size()}; }
  std::span<const std::uint32_t> partners() const { return {nbr_.data(), nbr_.size()}; }
  std::size_t contacts() const { return nbr_.size(); }
  std::size_t candidates() const { return cand_.size(); }
  /// Calls f(i, j), i < j, for every contact, in canonical order (i, then j
  /// ascending).
  template <class F>
  void for_each_contact(F&& f) const {
    for (std::size_t i = 0; i + 1 < start_.size(); ++i)
      for (std::uint32_t m = start_[i]; m < start_[i + 1]; ++m) f(static_cast<std::uint32_t>(i), nbr_[m]);
  }
  /// The spheres as the test sees them: centres relative to the origin,
  /// wrapped on periodic axes.
  std::span<const Sphere<D>> spheres() const { return {s_.data(), s_.size()}; }
  /// The image shift of pair (i, j): x_j - x_i + shift is the minimum-image
  /// displacement from i to j (0 or +-side on each periodic axis); what the
  /// relative velocity across a moving periodic boundary needs.
  Vec image_shift(std::uint32_t i, std::uint32_t j) const {
    if (box_.triclinic) {
      const TiltedBox<D> tb = tilted_box(box_);
      Vec n;
      detail::nearest_image<D>(tb, s_[i].x, s_[j].x, tb.image_reach(s_[i].r + s_[j].r), n);
      return tb.cartesian(n);
    }
    Vec out{};
    for (int k = 0; k < D; ++k)
      if (box_.periodic[k]) {
        const double dx = s_[j].x[k] - s_[i].x[k];
        out[k] = detail::min_image(dx, box_.side[k]) - dx;
      }
    return out;
  }
  /// The minimum-image displacement x_j - x_i, as the test computes it.
  Vec displacement(std::uint32_t i, std::uint32_t j) const {
    Vec d;
    if (box_.triclinic) {
      const Vec sh = image_shift(i, j);
      for (int k = 0; k < D; ++k) d[k] = s_[j].x[k] - s_[i].x[k] + sh[k];
      return d;
    }
    for (int k = 0; k < D; ++k) {
      d[k] = s_[j].x[k] - s_[i].x[k];
      if (box_.periodic[k]) d[k] = detail::min_image(d[k], box_.side[k]);
    }
    return d;
  }
  const ContactListStats& stats() const { return stats_; }
  const ContactListParams& params() const { return params_; }
  /// Cell sizes of the grid of the last build (empty before the first).
  std::vector<double> grid_sizes() const {
    if (gw_) return gw_->sizes();
    if (gp_) return gp_->sizes();
    return {};
  }

 private:
  /// How far ahead update(positions, radii) asks for its input.
  static constexpr std::size_t kReadAhead = 32;
  /// Margins are compared with this much slack, relative to the box: the
  /// wrap and the differences round by a few units in the last place.
  static constexpr double kRoundingSlack = 1e-12;

  static void check_box(const ListBox<D>& box) {
    for (int k = 0; k < D; ++k) {
      if (!(std::isfinite(box.side[k]) && box.side[k] > 0))
        throw InputError("box", "side " + std::to_string(k + 1) + " must be finite and > 0 (got " +
                                    format_number(box.side[k]) + ")");
      if (!std::isfinite(box.origin[k]))
        throw InputError("origin", "coordinate " + std::to_string(k + 1) + " must be finite");
    }
    if (box.triclinic) {
      for (int k = 0; k < D; ++k)
        if (!box.periodic[k]) throw InputError("periodic", "a triclinic box is periodic on every axis");
      tilted_box(box).check();  // finite tilts within LAMMPS's limit
    }
  }
  static TiltedBox<D> tilted_box(const ListBox<D>& b) {
    TiltedBox<D> t{b.side, b.tilt};
    if constexpr (D == 2) t.tilt[1] = t.tilt[2] = 0;
    return t;
  }

  double inflated(double r) const { return r * (1 + params_.skin_rel) + 0.5 * params_.skin; }

  /// Keeps m1 <= m2 the two smallest values seen, given one more.
  static void two_smallest(double m, double& m1, double& m2) {
    if (m < m1) {
      m2 = m1;
      m1 = m;
    } else if (m < m2) {
      m2 = m;
    }
  }

  /// Blocks of rows (one per thread, at most one per kMinRowsPerThread).
  std::size_t blocks_for(std::size_t n) const {
    return std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(threads_), n / kMinRowsPerThread));
  }
  static constexpr std::size_t kMinRowsPerThread = 2048;
  /// The displacement check's filter (update_from): a particle whose margin
  /// is surely above the second smallest so far skips its square root:
  /// u2 below (a - m2)^2 by a relative kSqrtSkipRel, where a - m2 exceeds
  /// kSqrtSkipGuard |a| (so that the gap, 5e-10 (a - m2) > 5e-15 |a|, is
  /// far beyond the rounding of a - sqrt(u2), ~3e-16 (|a| + |u|)).
  static constexpr double kSqrtSkipRel = 1e-9;
  static constexpr double kSqrtSkipGuard = 1e-5;

  template <class Get>
  bool update_from(std::size_t n, Get&& get) {
    if (n >= (std::size_t{1} << 31)) throw InputError("n", "at most 2^31 - 1 particles");
    auto t0 = Clock::now();
    // Read and check every particle into next_, and find the two smallest
    // margins, on blocks of particles; nothing of the list changes before
    // every particle has passed.
    next_.resize(n);
    raw_.resize(n);
    const bool same_count = built_ && n == xref_.size();
    // No skin: rebuilt at every update, and the grid's pairs are the contacts.
    const bool exact = params_.skin == 0 && params_.skin_rel == 0;
    const std::size_t B = blocks_for(n);
    block_min_.assign(2 * B, std::numeric_limits<double>::infinity());
    block_error_.assign(B, nullptr);
    const TiltedBox<D> tb = tilted_box(box_);
    const ListBox<D> bx = box_;  // in a local: the loop's stores could alias a member, reloaded every particle
    const double* const rbig = rbig_.data();
    const Vec* const xref = xref_.data();
    Sphere<D>* const next = next_.data();
    Vec* const raw = raw_.data();
    // The reference of the displacements: on a periodic axis the wrapped
    // centre (images are then at most one side away, whose change the box
    // term bounds; an unwrapped coordinate many sides out moves with every
    // change of the side), on a walled one the user's coordinate (a moving
    // wall moves no particle).
    const auto raw_of = [&](auto triclinic, const Sphere<D>& q, const Sphere<D>& local) {
      Vec w;
      if constexpr (decltype(triclinic)::value) {
        std::array<double, D> f = tb.fractional(local.x);
        for (auto& v : f) v -= std::floor(v);
        w = tb.cartesian(f);  // the centre wrapped into the lattice's cell
      } else {
        for (int k = 0; k < D; ++k) w[k] = bx.periodic[k] ? local.x[k] : q.x[k];
      }
      return w;
    };
    // Stored by the loop only when a build is certain; else by a second
    // pass if the check calls for one (most steps do not: their writes
    // were a third of the loop's memory traffic).
    const bool raw_now = !same_count || exact;
    // The loop compiled twice, for a triclinic box and for the others.
    const auto read = [&](auto triclinic) {
      detail::parallel_for(static_cast<int>(B), B, [&](std::size_t b, int) {
        const std::size_t i0 = n * b / B, i1 = n * (b + 1) / B;
        double m1 = std::numeric_limits<double>::infinity(), m2 = m1;
        try {
          for (std::size_t i = i0; i < i1; ++i) {
            const Sphere<D> q = get(i);
            if (!(std::isfinite(q.r) && q.r > 0))
              throw InputError("radius", "particle " + std::to_string(i) + " has radius " + format_number(q.r) +
                                             " (must be finite and > 0)");
            Sphere<D> local;
            local.r = q.r;
            for (int k = 0; k < D; ++k) {
              if (!std::isfinite(q.x[k]))
                throw InputError("position", "particle " + std::to_string(i) + " has a non-finite coordinate on axis " +
                                                 std::to_string(k + 1));
              const double x = q.x[k] - bx.origin[k];
              if constexpr (decltype(triclinic)::value) {
                local.x[k] = x;  // the tilted grid's test takes the centres as they are
              } else if (bx.periodic[k]) {
                local.x[k] = detail::wrap(x, bx.side[k]);
              } else {
                if (x < 0 || x > bx.side[k])
                  throw InputError("position", "particle " + std::to_string(i) + " left the walled axis " +
                                                   std::to_string(k + 1) + ": its centre " + format_number(q.x[k]) +
                                                   " is outside [" + format_number(bx.origin[k]) + ", " +
                                                   format_number(bx.origin[k] + bx.side[k]) + "]");
                local.x[k] = x;
              }
            }
            next[i] = local;
            const Vec rw = raw_of(triclinic, q, local);
            if (raw_now) {
              raw[i] = rw;
            } else {
              double u2 = 0;
              if constexpr (decltype(triclinic)::value) {  // the nearest lattice image of the displacement
                const Vec sh = tb.cartesian(detail::nearest_shift<D>(tb, xref[i], rw));
                for (int k = 0; k < D; ++k) {
                  const double u = rw[k] - xref[i][k] + sh[k];
                  u2 += u * u;
                }
              } else {
                for (int k = 0; k < D; ++k) {
                  double u = rw[k] - xref[i][k];
                  if (bx.periodic[k]) u = detail::min_image(u, bx.side[k]);
                  u2 += u * u;
                }
              }
              // The margin a - |u| matters only below m2: the square root
              // is taken only where it could be (u2 within a relative 1e-9
              // of (a - m2)^2 or above; rounding cannot bridge that gap),
              // so the two smallest are the same, bit for bit.
              const double a = rbig[i] - q.r, d = a - m2;
              if (!(d > kSqrtSkipGuard * std::abs(a) && u2 < d * d * (1 - kSqrtSkipRel)))
                two_smallest(a - std::sqrt(u2), m1, m2);
            }
          }
        } catch (...) {
          block_error_[b] = std::current_exception();
        }
        block_min_[2 * b] = m1;
        block_min_[2 * b + 1] = m2;
      });
    };
    if (bx.triclinic) read(std::true_type{});
    else read(std::false_type{});
    for (const auto& e : block_error_)
      if (e) std::rethrow_exception(e);  // blocks in index order: the lowest particle's error
    bool rebuild = !same_count || exact;
    double used = -1;  // the margin used up, when displacements call for the build
    if (!rebuild) {
      double m1 = std::numeric_limits<double>::infinity(), m2 = m1;
      for (const double m : block_min_) two_smallest(m, m1, m2);
      double shift = 0, scale = 0;  // how far the periodic sides' (and tilts') changes move an image
      for (int k = 0; k < D; ++k) scale = std::max(scale, box_.side[k] + std::abs(box_.origin[k]));
      if (box_.triclinic) {
        // The lattice's columns' changes times how many columns away a
        // candidate's image can lie along each: the centres wrapped into
        // the cell differ by less than one column in fractional terms, and
        // an image closer than 2 R_max by less than 2 R_max / width(k)
        // more (one column unless the box is narrower than 2 R_max).
        const TiltedBox<D> now = tilted_box(box_), then{side_built_, tilt_built_};
        for (int k = 0; k < D; ++k) {
          std::array<double, D> e{};
          e[k] = 1;
          const Vec a = now.cartesian(e), b = then.cartesian(e);
          double c2 = 0;
          for (int q = 0; q < D; ++q) c2 += (a[q] - b[q]) * (a[q] - b[q]);
          const double columns = std::max(1.0, std::ceil(2 * rbig_max_ * (1 + kImageReachRelMargin) / then.width(k)));
          shift += columns * std::sqrt(c2);
        }
      } else {
        double shift2 = 0;
        for (int k = 0; k < D; ++k)
          if (box_.periodic[k]) shift2 += (box_.side[k] - side_built_[k]) * (box_.side[k] - side_built_[k]);
        shift = std::sqrt(shift2);
      }
      rebuild = n > 1 && m1 + m2 <= shift + kRoundingSlack * (scale + 2 * rbig_max_);
      if (rebuild) used = std::max(0.0, margin_built_ - (m1 + m2));
    }
    if (rebuild && !raw_now) {  // the references the loop did not store
      const auto fill = [&](auto triclinic) {
        for (std::size_t i = 0; i < n; ++i) raw[i] = raw_of(triclinic, get(i), next[i]);
      };
      if (bx.triclinic) fill(std::true_type{});
      else fill(std::false_type{});
    }
    stats_.seconds_check += seconds_since(t0);
    if (rebuild) {
      t0 = Clock::now();
      const std::uint64_t since = stats_.steps - steps_built_;
      if (used >= 0 && since == 1 && since_built_ == 1 && xold_.size() == n) two_step_travel(n);
      build();  // may throw (sizes below the inflated diameters): nothing committed yet
      stats_.seconds_build += seconds_since(t0);
      ++stats_.builds;
      if (used >= 0) {
        stats_.travel += used;
        stats_.travel_steps += since;
      }
      since_built_ = used >= 0 ? since : 0;
    } else {
      s_.swap(next_);
    }
    t0 = Clock::now();
    if (exact) {  // the build's search tested every pair with the same expression on the same spheres
      start_.assign(cstart_.begin(), cstart_.end());
      nbr_.resize(cand_.size());
      std::copy(cand_.begin(), cand_.end(), nbr_.begin());
    } else if (box_.triclinic) {
      test_tilted();
    } else {
      switch (mask_) {
        case 0: test<0>(); break;
        case 1: test<1>(); break;
        case 2: test<2>(); break;
        case 3: test<3>(); break;
        case 4: test<4>(); break;
        case 5: test<5>(); break;
        case 6: test<6>(); break;
        default: test<7>(); break;
      }
    }
    stats_.seconds_test += seconds_since(t0);
    ++stats_.steps;
    stats_.candidates = cand_.size();
    stats_.contacts = nbr_.size();
    stats_.candidates_tested += cand_.size();
    return rebuild;
  }

  /// The two largest displacements' sums of the update being read (raw_)
  /// since the last build (xref_, one step ago) and since the build before
  /// (xold_, two steps ago), added to the stats.
  void two_step_travel(std::size_t n) {
    const TiltedBox<D> tb = tilted_box(box_);
    const auto length = [&](const Vec& from, const Vec& to) {
      double u2 = 0;
      if (box_.triclinic) {
        const Vec sh = tb.cartesian(detail::nearest_shift<D>(tb, from, to));
        for (int k = 0; k < D; ++k) u2 += (to[k] - from[k] + sh[k]) * (to[k] - from[k] + sh[k]);
      } else {
        for (int k = 0; k < D; ++k) {
          double u = to[k] - from[k];
          if (box_.periodic[k]) u = detail::min_image(u, box_.side[k]);
          u2 += u * u;
        }
      }
      return std::sqrt(u2);
    };
    const double inf = std::numeric_limits<double>::infinity();
    double a1 = inf, a2 = inf, b1 = inf, b2 = inf;  // the two largest, negated as two_smallest keeps them
    for (std::size_t i = 0; i < n; ++i) {
      two_smallest(-length(xref_[i], raw_[i]), a1, a2);
      two_smallest(-length(xold_[i], raw_[i]), b1, b2);
    }
    stats_.travel_one -= a1 + a2;
    stats_.travel_two -= b1 + b2;
  }

  /// The candidates of the spheres in next_ (inflated), then commits them.
  void build() {
    const std::size_t n = next_.size();
    gs_.resize(n);
    double rmin = std::numeric_limits<double>::infinity(), rmax = 0;
    for (std::size_t i = 0; i < n; ++i) {
      gs_[i].x = next_[i].x;
      gs_[i].r = inflated(next_[i].r);
      rmin = std::min(rmin, gs_[i].r);
      rmax = std::max(rmax, gs_[i].r);
    }
    // The grid's box: a walled axis of a box with a periodic one is laid out
    // as periodic, padded so that no image of a walled axis comes within any
    // candidate distance (2 R_max) and every real candidate keeps its plain
    // difference (|dx| < 2 R_max <= side / 2).
    Extent<D> gbox;
    for (int k = 0; k < D; ++k)
      gbox[k] = box_.periodic[k] || mask_ == 0 ? box_.side[k]
                                               : std::max(box_.side[k] + 2 * rmax, 4 * rmax) * (1 + 1e-9);
    const int T = threads_;
    GridParams& gp = grid_params_;  // kept: assigning the sizes again allocates nothing
    gp.search = params_.search;
    gp.threads = T;
    if (params_.sizes.empty() && n > 0 &&
        (default_sizes_.empty() || default_sizes_.back() < 2 * rmax || default_sizes_.front() > 3 * rmin ||
         default_sizes_.front() < rmin / 2))
      default_sizes_ = doubling_sizes(rmin, rmax);
    if (params_.sizes.empty()) {
      gp.sizes = default_sizes_;
    } else {
      gp.sizes.resize(params_.sizes.size());
      for (std::size_t h = 0; h < gp.sizes.size(); ++h) gp.sizes[h] = inflated(0.5 * params_.sizes[h]) * 2;
    }
    for (auto& k : keys_) k.clear();
    if (!keys_of_ || pair_n_ != n) {
      keys_of_.emplace(n);
      pair_n_ = n;
    }
    const detail::PairKeys ps = *keys_of_;  // a copy: the sorts' stores below cannot change its shift
    const std::span<const Sphere<D>> gspan(gs_.data(), gs_.size());
    // The grid's pairs as keys, one list per thread, stored a batch at a
    // time (base/threads.hpp, kTakesBatches).
    struct Keys {
      std::vector<std::vector<std::uint64_t>>& keys;
      detail::PairKeys ps;
      void operator()(int t, std::uint32_t i, std::uint32_t j) { keys[static_cast<std::size_t>(t)].push_back(ps.key(i, j)); }
      void pairs(int t, std::span<const IndexPair> s) {
        std::vector<std::uint64_t>& out = keys[static_cast<std::size_t>(t)];
        const std::size_t at = out.size();
        out.resize(at + s.size());
        std::uint64_t* const o = out.data() + at;
        for (std::size_t k = 0; k < s.size(); ++k) o[k] = ps.key(s[k].first, s[k].second);
      }
    };
    const auto collect = [&](const auto& grid) {
      Keys sink{keys_, ps};
      grid.template for_each_pair<PairsOnly>(sink);
    };
    const auto search = [&](auto& grid) {
      const auto t0 = Clock::now();
      if (!grid || grid->params().sizes != gp.sizes) grid.emplace(gspan, gbox, gp);  // a new grid: new sizes
      else grid->rebuild(gspan, gbox);
      stats_.seconds_grid += seconds_since(t0);
      collect(*grid);
    };
    if (n > 0) {
      if (box_.triclinic) {
        // The tilted grid (grid/tilted.hpp): made anew at each build, as its
        // tilts change; a box narrower than the inflated spheres reach has
        // further images searched there and in the test.
        const auto t0 = Clock::now();
        gt_.emplace(gspan, tilted_box(box_), gp);
        stats_.seconds_grid += seconds_since(t0);
        collect(*gt_);
      } else if (mask_ == 0) {
        search(gw_);
      } else {
        search(gp_);
      }
    }
    // Canonical order as compressed rows: two counting sorts, by the second
    // index, then (stable) by the first, so every row comes out ascending
    // (an insertion sort of each row, branching on random partners, cost
    // twice the two passes: `pour_replay --profile-skin`).
    cstart_.assign(n + 1, 0);
    by_second_.assign(n + 1, 0);
    std::uint32_t* const cst = cstart_.data();  // raw arrays: the counts' stores alias no member
    std::uint32_t* const bys = by_second_.data();
    std::size_t total = 0;
    for (const auto& l : keys_) {
      total += l.size();
      for (const std::uint64_t k : l) {
        ++cst[ps.first(k) + 1];
        ++bys[ps.second(k) + 1];
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      cst[i + 1] += cst[i];
      bys[i + 1] += bys[i];
    }
    sorted_keys_.resize(total);
    std::uint64_t* const sk = sorted_keys_.data();
    for (const auto& l : keys_)
      for (const std::uint64_t k : l) sk[bys[ps.second(k)]++] = k;
    fill_.assign(cstart_.begin(), cstart_.end() - 1);
    cand_.resize(total);
    first_.resize(total);
    std::uint32_t* const fill = fill_.data();
    std::uint32_t* const cand = cand_.data();
    std::uint32_t* const first = first_.data();
    for (std::size_t c = 0; c < total; ++c) {
      const std::uint64_t k = sk[c];
      const std::uint32_t i = ps.first(k), at = fill[i]++;
      cand[at] = ps.second(k);
      first[at] = i;
    }
    // Commit.
    s_.swap(next_);
    xold_.swap(xref_);  // the build before's references, for two_step_travel
    xref_.swap(raw_);
    rbig_.resize(n);
    double rbig_max = 0;
    double m1 = std::numeric_limits<double>::infinity(), m2 = m1;
    for (std::size_t i = 0; i < n; ++i) {
      rbig_[i] = gs_[i].r;
      rbig_max = std::max(rbig_max, gs_[i].r);
      two_smallest(gs_[i].r - s_[i].r, m1, m2);
    }
    rbig_max_ = rbig_max;
    margin_built_ = n > 1 ? m1 + m2 : 0;
    steps_built_ = stats_.steps;
    for (int k = 0; k < D; ++k) side_built_[k] = box_.side[k];
    tilt_built_ = tilted_box(box_).tilt;
    built_ = true;
  }

  /// The per-step test in a triclinic box, with the tilted grid's own test
  /// (grid/tilted.hpp): the lattice image nearest in fractional terms, or,
  /// at zero tilt, the orthogonal grid's on the wrapped centres.
  void test_tilted() {
    const TiltedBox<D> tb = tilted_box(box_);
    if (!tb.tilted()) {
      wrapped_.resize(s_.size());
      for (std::size_t i = 0; i < s_.size(); ++i) {
        wrapped_[i].r = s_[i].r;
        for (int k = 0; k < D; ++k) wrapped_[i].x[k] = detail::wrap(s_[i].x[k], box_.side[k]);
      }
      test_with([w = wrapped_.data()](std::uint32_t i) { return w[i]; },
                [w = wrapped_.data(), side = box_.side](const Sphere<D>& p, std::uint32_t j) {
                  return detail::overlap_axes<D, (1u << D) - 1>(p, w[j], side);  // the grid's test (grid/geometry.hpp)
                });
      return;
    }
    double r_max = 0;
    for (const auto& p : s_) r_max = std::max(r_max, p.r);
    const std::array<int, D> reach = tb.image_reach(2 * r_max);  // shifts around the rounding (none in a wide box)
    test_with([s = s_.data()](std::uint32_t i) { return s[i]; },
              [&tb, &reach, s = s_.data()](const Sphere<D>& p, std::uint32_t j) {
                Vec sh;
                const double rs = p.r + s[j].r;
                return detail::nearest_image<D>(tb, p.x, s[j].x, reach, sh) < rs * rs;
              });
  }

  /// The per-step test of every candidate: contacts into start_ / nbr_.
  /// Four candidates at a time, in the order they are stored, whichever
  /// rows they belong to (grid/detail/overlap4.hpp, which grid/hgrid.hpp
  /// brings: each lane the scalar test's operations on its own two
  /// spheres): a loop of fixed steps, where rows of a few candidates each
  /// made a loop per row end at an unpredictable place. The contacts' rows
  /// are stored beside them and counted into start_ per block.
  template <unsigned Mask>
  void test() {
    const std::size_t n = s_.size();
    const std::size_t total = cand_.size();
    start_.resize(n + 1);
    nbr_.resize(total);  // at most every candidate; cut to the contacts below
    rows_.resize(total);
    const Sphere<D>* const s = s_.data();
    const Extent<D> side = box_.side;
    const std::uint32_t* const cs = cstart_.data();
    const std::uint32_t* const cand = cand_.data();
    const std::uint32_t* const first = first_.data();
    std::uint32_t* const out = nbr_.data();
    std::uint32_t* const rows = rows_.data();
    std::uint32_t* const st = start_.data();
    const std::size_t B = blocks_for(n);
    block_count_.resize(B + 1);
    // Block b: rows i0..i1 - 1, candidates m0..m1 - 1; its contacts at its
    // own candidates' place (never more than it has, and a four-lane store
    // at w <= m ends within m..m + 3).
    detail::parallel_for(static_cast<int>(B), B, [&](std::size_t b, int) {
      const std::size_t i0 = n * b / B, i1 = n * (b + 1) / B;
      const std::uint32_t m0 = cs[i0], m1 = cs[i1];
      std::uint32_t w = m0, m = m0;
      for (; m + 4 <= m1; m += 4) {
        const unsigned bits = detail::overlap4_pairs<D, Mask>(s, first + m, cand + m, side);
        detail::compress4(out + w, cand + m, bits);
        w += detail::compress4(rows + w, first + m, bits);
      }
      if (m < m1) {  // the block's last one to three, the lanes past them a copy of the first
        std::uint32_t fi[4], se[4], c_out[4], c_rows[4];
        for (std::uint32_t u = 0; u < 4; ++u) {
          fi[u] = first[m + (m + u < m1 ? u : 0)];
          se[u] = cand[m + (m + u < m1 ? u : 0)];
        }
        const unsigned bits = detail::overlap4_pairs<D, Mask>(s, fi, se, side) & ((1u << (m1 - m)) - 1);
        detail::compress4(c_out, se, bits);
        const unsigned k = detail::compress4(c_rows, fi, bits);
        for (unsigned u = 0; u < k; ++u) out[w + u] = c_out[u], rows[w + u] = c_rows[u];
        w += k;
      }
      // Each row's first contact: the rows' counts, then their sums.
      for (std::size_t i = i0; i < i1; ++i) st[i] = 0;
      for (std::uint32_t c = m0; c < w; ++c) ++st[rows[c]];
      std::uint32_t at = m0;
      for (std::size_t i = i0; i < i1; ++i) {
        const std::uint32_t k = st[i];
        st[i] = at;
        at += k;
      }
      block_count_[b] = w - m0;
    });
    join_blocks(B);
  }

  /// The per-step test one candidate at a time: row(i) once per particle
  /// (its sphere, kept in registers over its row), hit(row(i), j) per
  /// candidate; contacts into start_ / nbr_.
  template <class Row, class Hit>
  void test_with(Row&& row, Hit&& hit) {
    const std::size_t n = s_.size();
    start_.resize(n + 1);
    nbr_.resize(cand_.size());  // at most every candidate; cut to the contacts below
    const std::uint32_t* const cs = cstart_.data();
    const std::uint32_t* const cand = cand_.data();
    std::uint32_t* const out = nbr_.data();
    std::uint32_t* const st = start_.data();
    const std::size_t B = blocks_for(n);
    block_count_.resize(B + 1);
    // Block b writes its rows' contacts at its own candidates' place (never
    // more than it has), then the blocks move down into one run.
    detail::parallel_for(static_cast<int>(B), B, [&](std::size_t b, int) {
      const std::size_t i0 = n * b / B, i1 = n * (b + 1) / B;
      std::uint32_t w = cs[i0];
      for (std::size_t i = i0; i < i1; ++i) {
        st[i] = w;
        const Sphere<D> p = row(static_cast<std::uint32_t>(i));
        for (std::uint32_t m = cs[i]; m < cs[i + 1]; ++m) {
          const std::uint32_t j = cand[m];
          out[w] = j;
          w += hit(p, j);
        }
      }
      block_count_[b] = w - cs[i0];
    });
    join_blocks(B);
  }

  /// The blocks' contacts (block b's block_count_[b] at its first row's
  /// candidates' place, start_ of its rows pointing there) moved down into
  /// one run.
  void join_blocks(std::size_t B) {
    const std::size_t n = s_.size();
    const std::uint32_t* const cs = cstart_.data();
    std::uint32_t* const out = nbr_.data();
    std::uint32_t* const st = start_.data();
    std::uint32_t at = 0;
    for (std::size_t b = 0; b < B; ++b) {
      const std::size_t i0 = n * b / B, i1 = n * (b + 1) / B;
      const std::uint32_t from = cs[i0], count = block_count_[b];
      if (from != at) {
        std::memmove(out + at, out + from, count * sizeof(std::uint32_t));
        for (std::size_t i = i0; i < i1; ++i) st[i] -= from - at;
      }
      at += count;
    }
    st[n] = at;
    nbr_.resize(at);
  }

  ContactListParams params_;
  ListBox<D> box_{};
  unsigned mask_ = 0;  // bit k: axis k periodic
  int threads_ = 1;
  bool built_ = false;
  std::vector<Sphere<D>> s_, next_;  // the spheres as tested (local, wrapped); the update being read
  std::vector<Vec> xref_, raw_;      // displacements' references at the last build (see update_from); of the update being read
  std::vector<double> rbig_;         // inflated radii at the last build
  double rbig_max_ = 0;
  double margin_built_ = 0;        // the two smallest margins' sum at the last build
  std::uint64_t steps_built_ = 0;  // stats_.steps when it was made
  std::uint64_t since_built_ = 0;  // the steps between the last two builds, if displacements called the last; else 0
  std::vector<Vec> xold_;          // the references of the build before the last (two_step_travel)
  Extent<D> side_built_{};
  std::vector<Sphere<D>> gs_;        // the inflated spheres of a build
  std::vector<Sphere<D>> wrapped_;   // a triclinic box at zero tilt: the wrapped centres
  std::vector<double> default_sizes_;
  GridParams grid_params_;
  std::optional<HGrid<D, Boundary::walls>> gw_;     // every axis walled
  std::optional<HGrid<D, Boundary::periodic>> gp_;  // any axis periodic (walled ones padded)
  std::optional<TiltedHGrid<D>> gt_;                // a triclinic box
  std::array<double, 3> tilt_built_{};
  std::optional<detail::PairKeys> keys_of_;  // packs a pair into a key for indices below pair_n_
  std::size_t pair_n_ = 0;
  std::vector<std::uint32_t> fill_;          // a build's counting sort: each row's next free place
  std::vector<std::uint32_t> by_second_;     // a build's first counting sort: each second index's next place
  std::vector<std::uint64_t> sorted_keys_;   // a build's candidates by their second index
  std::vector<std::vector<std::uint64_t>> keys_;  // per thread of a build's search
  std::vector<std::uint32_t> cstart_, cand_;      // the candidates, compressed rows
  std::vector<std::uint32_t> first_;              // each candidate's row
  detail::UninitVector<std::uint32_t> rows_;      // each contact's row (the per-step test's)
  std::vector<std::uint32_t> start_;
  detail::UninitVector<std::uint32_t> nbr_;       // the contacts
  std::vector<std::uint32_t> block_count_;
  std::vector<double> block_min_;
  std::vector<std::exception_ptr> block_error_;
  ContactListStats stats_;
};

}  // namespace hgrid
