// An insertion-only hierarchical grid for the excluded-volume generators:
// levels by radius octave (r_min 2^l, r_min 2^(l+1)], per level a dense
// cell -> head table and one next-pointer list per cell. Answers "does this
// candidate sphere overlap any stored sphere at level >= l?" (largest-first
// insertion only needs the levels at or above the candidate's own).
//
// A second layout serves the checkerboard Monte Carlo (gen_equilibrate.cpp):
// the box is cut into domains at least one largest diameter wide, shifted by
// an origin, and every level's cells nest in the domains, so a domain's
// lists are written only by moves of its own particles.
//
// visit_box serves the event chains (gen_event_chain.hpp): the spheres of a
// level filed in the cells a moving sphere's path can reach.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "hgridlab/grid/geometry.hpp"

namespace hgrid::detail {

template <int D, Boundary B>
class InsertGrid {
 public:
  static constexpr std::uint32_t kEmpty = 0xffffffffu;
  /// Cells per stored particle a level may use at most (memory bound: 4 bytes
  /// a cell); fewer when the level's particles are larger than the cells.
  static constexpr double kCellsPerParticle = 2.0;

  /// radii: every radius that will be inserted (any order), for the level sizes.
  InsertGrid(const Extent<D>& box, const std::vector<double>& radii) : box_(box) {
    r0_ = *std::min_element(radii.begin(), radii.end());
    const double rmax = *std::max_element(radii.begin(), radii.end());
    const int L = std::max(1, level_of_raw(rmax) + 1);
    levels_.resize(L);
    std::vector<std::size_t> count(L, 0);
    for (double r : radii) {
      const int l = level_of(r);
      ++count[l];
      levels_[l].rmax = std::max(levels_[l].rmax, r);
    }
    double geo = 1;
    for (int k = 0; k < D; ++k) geo *= box[k];
    geo = std::pow(geo, 1.0 / D);
    geo_ = geo;
    for (int l = 0; l < L; ++l) {
      Level& lv = levels_[l];
      lv.count = count[l];
      std::size_t cells = 1;
      for (int k = 0; k < D; ++k) {
        const double by_size = lv.rmax > 0 ? std::floor(box[k] / (2 * lv.rmax)) : 1.0;
        const double by_count = std::floor(box[k] / geo * std::pow(kCellsPerParticle * count[l] + 1, 1.0 / D));
        lv.n[k] = static_cast<std::int64_t>(std::max(1.0, std::min(by_size, by_count)));
        lv.s[k] = box[k] / static_cast<double>(lv.n[k]);
        cells *= static_cast<std::size_t>(lv.n[k]);
      }
      lv.head.assign(cells, kEmpty);
    }
    nodes_.assign(radii.size(), Node{});
  }

  /// The domain layout: `domains[k]` domains of width `width[k]` per axis
  /// (with walls one more than fit the box: the origin shifts them), each
  /// level with a whole number of cells per domain, as many as fit at least
  /// the level's largest radius wide (a scan's reach is r + r_max, whatever
  /// the cell size) and at most kCellsPerParticle per sphere of the level
  /// over the box. Cells start at the origin given to reset(). (Cells a
  /// diameter wide, the first layout's, left the largest levels one cell per
  /// domain: 8-cell lists that every small sphere's scan walked.)
  InsertGrid(const Extent<D>& box, const std::vector<double>& radii, const Extent<D>& width,
             const std::array<std::int64_t, D>& domains)
      : InsertGrid(box, radii) {
    for (Level& lv : levels_) {
      std::size_t cells = 1;
      for (int k = 0; k < D; ++k) {
        const double by_size = lv.rmax > 0 ? std::floor(width[k] / lv.rmax) : 1.0;
        const double by_count =
            std::floor(width[k] / geo_ * std::pow(kCellsPerParticle * static_cast<double>(lv.count) + 1, 1.0 / D));
        lv.m[k] = static_cast<std::int64_t>(std::max(1.0, std::min(by_size, by_count)));
        lv.n[k] = domains[k] * lv.m[k];
        lv.s[k] = width[k] / static_cast<double>(lv.m[k]);
        cells *= static_cast<std::size_t>(lv.n[k]);
      }
      lv.head.assign(cells, kEmpty);
    }
  }

  /// Empties the grid and moves the cells' origin to `origin` (periodic: in
  /// [0, domain width), and 0 on an axis with one domain, so that a scan
  /// wraps at most once; walls: in [-width, 0), the cells covering the box).
  void reset(const Extent<D>& origin) {
    for (Level& lv : levels_) {
      lv.o = origin;
      std::fill(lv.head.begin(), lv.head.end(), kEmpty);
    }
  }

  /// The domain (per-axis index, linearised) of a sphere of level l
  /// (level_of of its radius) at x: the domain of its cell at its level,
  /// for cells that start at `origin` (as reset() would place them),
  /// whatever origin the grid's cells have now.
  std::size_t domain_at(const std::array<double, D>& x, int l, const Extent<D>& origin) const {
    const Level& lv = levels_[l];
    std::size_t c = 0;
    for (int k = D - 1; k >= 0; --k)
      c = c * static_cast<std::size_t>(lv.n[k] / lv.m[k]) +
          static_cast<std::size_t>(coord(lv, x[k], k, origin[k]) / lv.m[k]);
    return c;
  }

  int levels() const { return static_cast<int>(levels_.size()); }
  /// Numbers n spheres (sphere i at x_of(i), of level level[i]) in the order
  /// of the cells they would be filed under, level by level (a counting
  /// sort; spheres of one cell keep their order): rank[i]. Inserting sphere
  /// i as node rank[i] puts the spheres a scan meets near each other in
  /// memory.
  template <class XOf>
  void rank_by_cell(std::size_t n, XOf&& x_of, const std::vector<int>& level, std::vector<std::uint32_t>& rank) {
    std::vector<std::size_t> first(levels_.size() + 1, 0);
    for (std::size_t l = 0; l < levels_.size(); ++l) first[l + 1] = first[l] + levels_[l].head.size();
    sort_start_.assign(first.back() + 1, 0);
    sort_key_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      sort_key_[i] = first[level[i]] + cell_of(levels_[level[i]], x_of(i));
      ++sort_start_[sort_key_[i] + 1];
    }
    for (std::size_t c = 1; c < sort_start_.size(); ++c) sort_start_[c] += sort_start_[c - 1];
    rank.resize(n);
    for (std::size_t i = 0; i < n; ++i) rank[i] = static_cast<std::uint32_t>(sort_start_[sort_key_[i]]++);
  }
  int level_of(double r) const { return std::min(levels() - 1, level_of_raw(r)); }

  /// Stores sphere `id` (ids 0..n-1, each once).
  void insert(std::uint32_t id, const std::array<double, D>& x, double r) { insert(id, x, r, level_of(r)); }
  /// The same with its level given (level_of(r)).
  void insert(std::uint32_t id, const std::array<double, D>& x, double r, int level) {
    Node& nd = nodes_[id];
    nd.x = x;
    nd.r = r;
    nd.level = level;
    link(id);
  }

  /// True if (x, r) overlaps (distance < r + r_q) a stored sphere at a level
  /// >= from_level, other than `skip`.
  bool overlaps(const std::array<double, D>& x, double r, int from_level, std::uint32_t skip = kEmpty) const {
    for (int l = from_level; l < levels(); ++l)
      if (overlaps_level(l, x, r, skip)) return true;
    return false;
  }

  /// Calls f(id, position, radius) for every stored sphere of level l filed
  /// in a cell that meets the box [x + lo, x + hi] (lo <= 0 <= hi per axis;
  /// periodic: the box shorter than the side, or taken as the whole axis),
  /// each sphere once; f returns false to stop. A superset of the spheres
  /// whose centres lie in the box.
  template <class F>
  void visit_box(int l, const std::array<double, D>& x, const std::array<double, D>& lo,
                 const std::array<double, D>& hi, F&& f) const {
    const Level& lv = levels_[l];
    std::array<std::int64_t, D> first, cnt;
    if (!box_cells(lv, x, lo, hi, first, cnt)) return;
    for_cells(lv, first, cnt, [&](std::size_t c) {
      for (std::uint32_t q = lv.head[c]; q != kEmpty;) {
        const Node& nd = nodes_[q];
        if (!f(q, nd.x, nd.r)) return false;
        q = nd.next;
      }
      return true;
    });
  }

  /// visit_box for a visitor that takes every sphere (f returns nothing):
  /// the cells' heads are read a batch at a time and their first nodes
  /// fetched before the lists are walked, so the walks' first loads (most
  /// lists hold one or two spheres) overlap instead of waiting in turn.
  template <class F>
  void visit_box_all(int l, const std::array<double, D>& x, const std::array<double, D>& lo,
                     const std::array<double, D>& hi, F&& f) const {
    const Level& lv = levels_[l];
    std::array<std::int64_t, D> first, cnt;
    if (!box_cells(lv, x, lo, hi, first, cnt)) return;
    constexpr int kBatch = 32;
    std::array<std::uint32_t, kBatch> heads;
    int held = 0;
    const auto walk = [&] {
      for (int h = 0; h < held; ++h)
        for (std::uint32_t q = heads[static_cast<std::size_t>(h)]; q != kEmpty;) {
          const Node& nd = nodes_[q];
          f(q, nd.x, nd.r);
          q = nd.next;
        }
      held = 0;
    };
    for_cells(lv, first, cnt, [&](std::size_t c) {
      const std::uint32_t q = lv.head[c];
      if (q != kEmpty) {
        __builtin_prefetch(&nodes_[q]);
        heads[static_cast<std::size_t>(held++)] = q;
        if (held == kBatch) walk();
      }
      return true;
    });
    walk();
  }
  /// The smallest radius the grid was made for.
  double rmin() const { return r0_; }
  /// The largest radius stored at level l (0 if none).
  double level_rmax(int l) const { return levels_[l].rmax; }

  /// Moves stored sphere id to x (erase, then insert at its own level: its
  /// radius and level are kept, not recomputed).
  void move(std::uint32_t id, const std::array<double, D>& x) {
    erase(id);
    nodes_[id].x = x;
    link(id);
  }

  /// Gives stored sphere id the radius r, of its own level (level_of(r) ==
  /// level(id)): its cell does not change.
  void set_radius(std::uint32_t id, double r) { nodes_[id].r = r; }

  /// Removes sphere id (it must be stored): an O(cell occupancy) unlink.
  void erase(std::uint32_t id) {
    Level& lv = levels_[nodes_[id].level];
    const std::size_t c = cell_of(lv, nodes_[id].x);
    std::uint32_t* link = &lv.head[c];
    while (*link != id) link = &nodes_[*link].next;
    *link = nodes_[id].next;
  }

  const std::array<double, D>& position(std::uint32_t id) const { return nodes_[id].x; }
  double radius(std::uint32_t id) const { return nodes_[id].r; }
  /// The level of stored sphere id (level_of of its radius).
  int level(std::uint32_t id) const { return nodes_[id].level; }

 private:
  struct Level {
    std::array<std::int64_t, D> n{};
    std::array<std::int64_t, D> m{};  // domain layout: cells per domain (else unused)
    std::array<double, D> s{};
    std::array<double, D> o{};        // where cell 0 starts
    double rmax = 0;
    std::size_t count = 0;  // spheres of the level
    std::vector<std::uint32_t> head;
  };

  /// The cells of a level that meet the box [x + lo, x + hi]: the first and
  /// the count per axis (periodic: a box as wide as the side or wider takes
  /// the whole axis once); false if none.
  [[gnu::always_inline]] static bool box_cells(const Level& lv, const std::array<double, D>& x, const std::array<double, D>& lo,
                        const std::array<double, D>& hi, std::array<std::int64_t, D>& first,
                        std::array<std::int64_t, D>& cnt) {
    if (lv.rmax == 0) return false;
    for (int k = 0; k < D; ++k) {
      first[k] = static_cast<std::int64_t>(std::floor((x[k] + lo[k] - lv.o[k]) / lv.s[k]));
      std::int64_t last = static_cast<std::int64_t>(std::floor((x[k] + hi[k] - lv.o[k]) / lv.s[k]));
      if constexpr (B == Boundary::walls) {
        first[k] = std::max<std::int64_t>(first[k], 0);
        last = std::min<std::int64_t>(last, lv.n[k] - 1);
      } else if (last - first[k] + 1 >= lv.n[k]) {
        first[k] = 0;
        last = lv.n[k] - 1;
      }
      cnt[k] = last - first[k] + 1;
      if (cnt[k] <= 0) return false;
    }
    return true;
  }

  /// Calls g(cell index) for the cells box_cells found, axis 0 fastest
  /// (periodic: wrapped); g returns false to stop.
  template <class G>
  [[gnu::always_inline]] static void for_cells(const Level& lv, const std::array<std::int64_t, D>& first,
                        const std::array<std::int64_t, D>& cnt, G&& g) {
    std::array<std::int64_t, D> off{};
    while (true) {
      std::size_t c = 0;
      for (int k = D - 1; k >= 0; --k) {
        std::int64_t i = first[k] + off[k];
        if constexpr (B == Boundary::periodic) {
          if (i < 0) i += lv.n[k];
          else if (i >= lv.n[k]) i -= lv.n[k];
        }
        c = c * static_cast<std::size_t>(lv.n[k]) + static_cast<std::size_t>(i);
      }
      if (!g(c)) return;
      int k = 0;
      while (k < D && ++off[k] == cnt[k]) off[k++] = 0;
      if (k == D) return;
    }
  }

  /// Cell index along axis k of coordinate x (x in the box): periodic, x - o
  /// is at least minus one domain (those cells are the last ones, wrapped);
  /// rounding can put it one past the last cell.
  static std::int64_t coord(const Level& lv, double x, int k) { return coord(lv, x, k, lv.o[k]); }
  static std::int64_t coord(const Level& lv, double x, int k, double o) {
    std::int64_t i = static_cast<std::int64_t>(std::floor((x - o) / lv.s[k]));
    if constexpr (B == Boundary::periodic)
      if (i < 0) i += lv.n[k];
    return std::clamp<std::int64_t>(i, 0, lv.n[k] - 1);
  }

  static std::size_t cell_of(const Level& lv, const std::array<double, D>& x) {
    std::size_t c = 0;
    for (int k = D - 1; k >= 0; --k)
      c = c * static_cast<std::size_t>(lv.n[k]) + static_cast<std::size_t>(coord(lv, x[k], k));
    return c;
  }

  /// Puts stored node id (its position and level set) at the head of its cell's list.
  void link(std::uint32_t id) {
    Node& nd = nodes_[id];
    Level& lv = levels_[nd.level];
    const std::size_t c = cell_of(lv, nd.x);
    nd.next = lv.head[c];
    lv.head[c] = id;
  }

  int level_of_raw(double r) const {
    const double t = std::log2(r / r0_);
    return t <= 0 ? 0 : static_cast<int>(std::floor(t * (1 - 1e-12)));
  }

  bool overlaps_level(int l, const std::array<double, D>& x, double r, std::uint32_t skip) const {
    const double beta = r + levels_[l].rmax;
    std::array<double, D> lo, hi;
    lo.fill(-beta);
    hi.fill(beta);
    bool hit = false;
    visit_box(l, x, lo, hi, [&](std::uint32_t q, const std::array<double, D>& xq, double rq) {
      if (q == skip) return true;
      const double rs = r + rq;
      hit = dist2<D, B>(x, xq, box_) < rs * rs;
      return !hit;
    });
    return hit;
  }

  Extent<D> box_;
  double geo_ = 1;  // the box's geometric mean side
  double r0_ = 1;
  std::vector<Level> levels_;
  /// A stored sphere and its cell list's next entry, together: a list walk
  /// touches one node per candidate (were three arrays: positions, radii,
  /// next pointers).
  struct Node {
    std::array<double, D> x{};
    double r = 0;
    std::uint32_t next = kEmpty;
    std::int32_t level = 0;
  };
  std::vector<Node> nodes_;
  std::vector<std::size_t> sort_key_, sort_start_;  // rank_by_cell's counting sort
};

}  // namespace hgrid::detail
