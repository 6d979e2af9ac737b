// An insertion-only hierarchical grid for the excluded-volume generators:
// levels by radius octave (r_min 2^l, r_min 2^(l+1)], per level a dense
// cell -> head table and one next-pointer list per cell. Answers "does this
// candidate sphere overlap any stored sphere at level >= l?" (largest-first
// insertion only needs the levels at or above the candidate's own).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "grid/geometry.hpp"

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
    for (int l = 0; l < L; ++l) {
      Level& lv = levels_[l];
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
    next_.assign(radii.size(), kEmpty);
    pos_.assign(radii.size(), {});
    rad_.assign(radii.size(), 0.0);
  }

  int levels() const { return static_cast<int>(levels_.size()); }
  int level_of(double r) const { return std::min(levels() - 1, level_of_raw(r)); }

  /// Stores sphere `id` (ids 0..n-1, each once).
  void insert(std::uint32_t id, const std::array<double, D>& x, double r) {
    Level& lv = levels_[level_of(r)];
    std::size_t c = 0;
    for (int k = D - 1; k >= 0; --k) {
      std::int64_t i = static_cast<std::int64_t>(std::floor(x[k] / lv.s[k]));
      i = std::clamp<std::int64_t>(i, 0, lv.n[k] - 1);
      c = c * static_cast<std::size_t>(lv.n[k]) + static_cast<std::size_t>(i);
    }
    pos_[id] = x;
    rad_[id] = r;
    next_[id] = lv.head[c];
    lv.head[c] = id;
  }

  /// True if (x, r) overlaps (distance < r + r_q) a stored sphere at a level
  /// >= from_level, other than `skip`.
  bool overlaps(const std::array<double, D>& x, double r, int from_level, std::uint32_t skip = kEmpty) const {
    for (int l = levels() - 1; l >= from_level; --l)
      if (overlaps_level(levels_[l], x, r, skip)) return true;
    return false;
  }

  /// Removes sphere id (it must be stored): an O(cell occupancy) unlink.
  void erase(std::uint32_t id) {
    Level& lv = levels_[level_of(rad_[id])];
    std::size_t c = 0;
    for (int k = D - 1; k >= 0; --k) {
      std::int64_t i = static_cast<std::int64_t>(std::floor(pos_[id][k] / lv.s[k]));
      i = std::clamp<std::int64_t>(i, 0, lv.n[k] - 1);
      c = c * static_cast<std::size_t>(lv.n[k]) + static_cast<std::size_t>(i);
    }
    std::uint32_t* link = &lv.head[c];
    while (*link != id) link = &next_[*link];
    *link = next_[id];
  }

  const std::array<double, D>& position(std::uint32_t id) const { return pos_[id]; }

 private:
  struct Level {
    std::array<std::int64_t, D> n{};
    std::array<double, D> s{};
    double rmax = 0;
    std::vector<std::uint32_t> head;
  };

  int level_of_raw(double r) const {
    const double t = std::log2(r / r0_);
    return t <= 0 ? 0 : static_cast<int>(std::floor(t * (1 - 1e-12)));
  }

  bool overlaps_level(const Level& lv, const std::array<double, D>& x, double r, std::uint32_t skip) const {
    if (lv.rmax == 0) return false;
    const double beta = r + lv.rmax;
    std::array<std::int64_t, D> lo, cnt;
    for (int k = 0; k < D; ++k) {
      lo[k] = static_cast<std::int64_t>(std::floor((x[k] - beta) / lv.s[k]));
      std::int64_t hi = static_cast<std::int64_t>(std::floor((x[k] + beta) / lv.s[k]));
      if constexpr (B == Boundary::walls) {
        lo[k] = std::max<std::int64_t>(lo[k], 0);
        hi = std::min<std::int64_t>(hi, lv.n[k] - 1);
      } else if (hi - lo[k] + 1 >= lv.n[k]) {
        lo[k] = 0;
        hi = lv.n[k] - 1;
      }
      cnt[k] = hi - lo[k] + 1;
      if (cnt[k] <= 0) return false;
    }
    std::array<std::int64_t, D> off{};
    while (true) {
      std::size_t c = 0;
      for (int k = D - 1; k >= 0; --k) {
        std::int64_t i = lo[k] + off[k];
        if constexpr (B == Boundary::periodic) {
          if (i < 0) i += lv.n[k];
          else if (i >= lv.n[k]) i -= lv.n[k];
        }
        c = c * static_cast<std::size_t>(lv.n[k]) + static_cast<std::size_t>(i);
      }
      for (std::uint32_t q = lv.head[c]; q != kEmpty; q = next_[q]) {
        if (q == skip) continue;
        const double rs = r + rad_[q];
        if (dist2<D, B>(x, pos_[q], box_) < rs * rs) return true;
      }
      int k = 0;
      while (k < D && ++off[k] == cnt[k]) off[k++] = 0;
      if (k == D) break;
    }
    return false;
  }

  Extent<D> box_;
  double r0_ = 1;
  std::vector<Level> levels_;
  std::vector<std::uint32_t> next_;
  std::vector<std::array<double, D>> pos_;
  std::vector<double> rad_;
};

}  // namespace hgrid::detail
