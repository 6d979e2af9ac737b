// Verlet lists (Verlet, Phys. Rev. 159 (1967) 98; Allen & Tildesley,
// Computer Simulation of Liquids (1987) sect. 5.3.1) for the overlap tests
// of the hard-sphere Monte Carlo (gen_equilibrate.cpp): a small sphere's
// trial position is tested against the spheres of its list, and against
// the grid's levels of large spheres, instead of every sphere in the
// insertion grid's cells around it.
//
// The listed nodes are those of the grid's lowest levels, up to spheres of
// kListMaxRadius smallest radii (the "listed levels"); the larger spheres
// are few, their moves long, and they stay on the grid: every test scans
// the levels above the listed ones as before.
//
// Each listed node a has a reference position x0_a and radius rho_a, those
// it had when its list was made, and a budget h_a = kListHalfSkin rho_a.
// Its list holds every listed node b with |x0_a - x0_b| < (rho_a + rho_b)
// (1 + kListHalfSkin), and the lists are symmetric. While every listed node
// b keeps |x_b - x0_b| + max(0, r_b - rho_b) <= h_b, a sphere of radius r
// at x with |x - x0_a| + max(0, r - rho_a) <= h_a overlaps no listed node
// outside the list of a: |x - x_b| >= |x0_a - x0_b| - |x - x0_a| - |x_b -
// x0_b| >= r + r_b. So the test is the grid's test, exactly: the lists
// change how fast a trial is decided, never its outcome. (The radius term:
// a swap of two spheres of one level exchanges their radii between the two
// nodes, each keeping its place.) A node moved or grown beyond its budget
// is relisted at once: new reference, new list (found on the grid), and it
// joins its new neighbours' lists. A node whose list ran out of room is
// "unlisted": its own trials are tested on the grid. One thread: the
// checkerboard's domains run in turn (on several threads the grid alone
// tests the trials, and a list could name a sphere of another domain that
// moves meanwhile). The margins (kListMargin) keep the argument true in
// floating point: budgets are tested against h (1 - kListMargin), lists
// reach (1 + kListMargin) further.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "hgridlab/packing/detail/gen_insert_grid.hpp"
#include "hgridlab/packing/detail/gen_pairs.hpp"

namespace hgrid::detail {

/// A node's half skin h_a, relative to its radius: a trial moves a sphere by
/// at most kMcStep r per axis, so budgets in proportion to the radius cover
/// as large a share of every sphere's trials (docs/record/PERFORMANCE.md round 39).
inline constexpr double kListHalfSkin = 0.75;
/// The listed levels: those whose spheres are at most this many smallest
/// radii (docs/record/PERFORMANCE.md round 39).
inline constexpr double kListMaxRadius = 8.0;
/// Relative margins of the budget test and the lists' reach (see above).
inline constexpr double kListMargin = 1e-6;

template <int D, Boundary B>
class MoveLists {
 public:
  using Vec = std::array<double, D>;
  using Grid = InsertGrid<D, B>;

  /// half_skin: h_a / rho_a.
  MoveLists(const Extent<D>& box, double half_skin)
      : box_(box), budget_(half_skin * (1 - kListMargin)), grow_(1 + half_skin * (1 + kListMargin)) {}

  /// Lists for the nodes of the listed levels of `grid` (nodes 0..n-1
  /// stored), references where the nodes are: the pairs found with the
  /// HGrid on `threads` threads; every node of those levels listed.
  void build(const Grid& grid, std::size_t n, int threads) {
    const double r0 = grid.rmin();
    levels_ = 0;
    while (levels_ < grid.levels() && grid.level_rmax(levels_) <= kListMaxRadius * r0) ++levels_;
    x0_.resize(n);
    rho_.resize(n);
    std::vector<Sphere<D>> s;
    std::vector<std::uint32_t> node;  // s[m] is node node[m]
    for (std::size_t a = 0; a < n; ++a) {
      const auto id = static_cast<std::uint32_t>(a);
      x0_[a] = grid.position(id);
      rho_[a] = grid.radius(id);
      if (grid.level(id) >= levels_) continue;
      s.push_back(Sphere<D>{x0_[a], rho_[a] * grow_});
      node.push_back(id);
    }
    const int T = std::max(1, threads);
    std::vector<std::vector<std::uint64_t>> found(static_cast<std::size_t>(T));
    if (s.size() >= 2)
      for_each_overlapping<D, B>(
          std::span<const Sphere<D>>(s), box_,
          [&](int t, std::uint32_t i, std::uint32_t j) {
            found[static_cast<std::size_t>(t)].push_back(std::uint64_t{node[i]} << 32 | node[j]);
          },
          T);
    len_.assign(n, 0);
    for (const auto& f : found)
      for (const std::uint64_t p : f) {
        ++len_[p >> 32];
        ++len_[p & 0xffffffffu];
      }
    begin_.assign(n + 1, 0);
    for (std::size_t a = 0; a < n; ++a)
      begin_[a + 1] = begin_[a] + (grid.level(static_cast<std::uint32_t>(a)) < levels_
                                       ? len_[a] + std::max<std::uint32_t>(8, len_[a] / 2)
                                       : 0);
    entry_.resize(begin_[n]);
    std::fill(len_.begin(), len_.end(), 0);
    for (const auto& f : found)
      for (const std::uint64_t p : f) {
        const auto i = static_cast<std::uint32_t>(p >> 32), j = static_cast<std::uint32_t>(p & 0xffffffffu);
        entry_[begin_[i] + len_[i]++] = j;
        entry_[begin_[j] + len_[j]++] = i;
      }
    listed_.assign(n, 0);
    for (const std::uint32_t a : node) listed_[a] = 1;
    unlisted_ = 0;
    relisted_ = 0;
  }

  /// The listed levels: 0 .. levels() - 1; a test on a list scans the grid
  /// from level levels() up.
  int levels() const { return levels_; }
  /// Listed nodes whose lists ran out of room, and relists, since build().
  std::size_t unlisted() const { return unlisted_; }
  std::size_t relisted() const { return relisted_; }

  /// Whether node a (of a listed level) may be tested on its list with
  /// radius ra at x: a is listed and within its budget.
  bool covers(std::uint32_t a, const Vec& x, double ra) const { return listed_[a] && within(a, x, ra); }
  /// Whether node a (of a listed level) with radius ra at x is within its budget.
  bool within(std::uint32_t a, const Vec& x, double ra) const {
    const double h = budget_ * rho_[a] - std::max(0.0, ra - rho_[a]);
    return h >= 0 && dist2<D, B>(x, x0_[a], box_) <= h * h;
  }

  /// Whether a sphere of radius r at x overlaps a node of a's list other
  /// than `skip`, at its position in the grid (the listed levels; the caller
  /// scans the others).
  bool overlaps(const Grid& grid, std::uint32_t a, const Vec& x, double r, std::uint32_t skip = Grid::kEmpty) const {
    const std::uint32_t* e = entry_.data() + begin_[a];
    for (std::uint32_t m = 0, end = len_[a]; m < end; ++m) {
      const std::uint32_t b = e[m];
      const double rs = r + grid.radius(b);
      if (b != skip && dist2<D, B>(x, grid.position(b), box_) < rs * rs) return true;
    }
    return false;
  }

  /// Node a (of a listed level) gets its position and radius as reference
  /// and a new list, found on the grid, and joins its new neighbours'
  /// lists. Every other listed node must be within its budget, and every
  /// node's rho must not exceed the largest radius of its level in the
  /// grid.
  void relist(const Grid& grid, std::uint32_t a) {
    ++relisted_;
    const Vec xa = grid.position(a);
    const double ra = grid.radius(a);
    x0_[a] = xa;
    rho_[a] = ra;
    found_.clear();
    // The nodes to list lie within (rho_a + rho_b) g of x0_a by their
    // references (g = 1 + h / rho), so within (rho_a + rho_b) g + h_b by
    // their positions, with rho_b and h_b / (g - 1) at most r_l.
    Vec lo, hi;
    for (int l = 0; l < levels_; ++l) {
      const double rl = grid.level_rmax(l);
      if (rl == 0) continue;
      const double reach = ((ra + rl) * grow_ + (grow_ - 1) * rl) * (1 + kListMargin);
      lo.fill(-reach);
      hi.fill(reach);
      grid.visit_box_all(l, xa, lo, hi, [&](std::uint32_t b, const Vec&, double) {
        if (b == a) return;
        const double c = (ra + rho_[b]) * grow_;
        if (dist2<D, B>(xa, x0_[b], box_) < c * c) found_.push_back(b);
      });
    }
    if (found_.size() <= capacity(a)) {
      std::copy(found_.begin(), found_.end(), entry_.begin() + begin_[a]);
      len_[a] = static_cast<std::uint32_t>(found_.size());
      set_listed(a, true);
    } else {
      set_listed(a, false);
    }
    for (const std::uint32_t b : found_) {
      const auto first = entry_.begin() + begin_[b], last = first + len_[b];
      if (std::find(first, last, a) != last) continue;
      if (len_[b] < capacity(b)) entry_[begin_[b] + len_[b]++] = a;
      else set_listed(b, false);
    }
  }

 private:
  std::uint32_t capacity(std::uint32_t a) const { return begin_[a + 1] - begin_[a]; }
  void set_listed(std::uint32_t a, bool on) {
    if (on && !listed_[a]) --unlisted_;
    if (!on && listed_[a]) ++unlisted_;
    listed_[a] = on ? 1 : 0;
  }

  Extent<D> box_;
  double budget_, grow_;  // h_a / rho_a for the budget test; 1 + h_a / rho_a for the lists' reach (with margins)
  int levels_ = 0;        // the listed levels
  std::vector<Vec> x0_;                 // references
  std::vector<double> rho_;             // radii when listed
  std::vector<std::uint32_t> begin_, len_, entry_;
  std::vector<char> listed_;
  std::size_t unlisted_ = 0, relisted_ = 0;
  std::vector<std::uint32_t> found_;
};

}  // namespace hgrid::detail
