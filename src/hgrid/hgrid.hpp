// The hierarchical grid (HGrid) of Krijgsman, Ogarko & Luding (2014), Sect. 2:
// a value type built from a span of spheres, a box and one params struct.
#pragma once
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "hgrid/counters.hpp"
#include "hgrid/detail/levels.hpp"
#include "hgrid/detail/stencil.hpp"
#include "hgrid/error.hpp"
#include "hgrid/geometry.hpp"
#include "hgrid/params.hpp"

namespace hgrid {

/// D = 2 or 3; B = walls or periodic. Construction maps every particle to its
/// level of insertion (lowest h with 2 r <= s_h, Eq. 3) and cell (Eq. 1), and
/// stores the particles sorted by (level, cell) with one flat directory of
/// cell start offsets filled by a counting sort.
template <int D, Boundary B>
class HGrid {
  static_assert(D == 2 || D == 3, "HGrid supports d = 2 and d = 3");

 public:
  HGrid(std::span<const Sphere<D>> spheres, const Extent<D>& box, const GridParams& params);

  /// Hands every overlapping pair (distance < r_i + r_j; minimum image in a
  /// periodic box) to f(i, j) exactly once, with i < j the input indices.
  /// Search direction and counting are compile-time policies.
  template <Search S, class Count = Uncounted, class F>
  Counters query(F&& f) const;

  /// Same, with the direction of the params struct.
  template <class Count = Uncounted, class F>
  Counters for_each_pair(F&& f) const {
    return params_.search == Search::top_down ? query<Search::top_down, Count>(f)
                                              : query<Search::bottom_up, Count>(f);
  }

  int levels() const { return static_cast<int>(levels_.size()); }
  std::size_t size() const { return sorted_.size(); }
  /// Cell sizes actually used (periodic boxes fit an integer number of cells
  /// per axis, so a size can grow; the smallest side per level is reported).
  std::vector<double> sizes() const {
    std::vector<double> out;
    for (const auto& L : levels_) out.push_back(L.s_min);
    return out;
  }
  std::vector<std::uint64_t> particles_per_level() const {
    std::vector<std::uint64_t> out;
    for (std::size_t h = 0; h < levels_.size(); ++h) out.push_back(level_begin_[h + 1] - level_begin_[h]);
    return out;
  }
  /// Cells of level h (0-based) holding 0, 1, and 2 or more particles.
  std::array<std::uint64_t, 3> occupancy(int h) const {
    const auto& lv = levels_.at(h);
    std::array<std::uint64_t, 3> out{lv.cells(), 0, 0};
    for_each_cell(lv, [&](std::uint64_t b, std::uint64_t) {
      --out[0];
      ++out[start_[b + 1] - start_[b] >= 2 ? 2 : 1];
    });
    return out;
  }
  const GridParams& params() const { return params_; }
  const Extent<D>& box() const { return box_; }
  /// Bytes held by the grid, including its sorted copy of the particles.
  std::size_t memory_bytes() const {
    return sorted_.capacity() * sizeof(Sphere<D>) + id_.capacity() * sizeof(std::uint32_t) +
           start_.capacity() * sizeof(std::uint32_t) + keys_.capacity() * sizeof(std::uint64_t) +
           words_.capacity() * sizeof(std::uint64_t) + rank_.capacity() * sizeof(std::uint32_t) +
           levels_.capacity() * sizeof(detail::Level<D>);
  }

 private:
  using Coords = std::array<std::int64_t, D>;

  std::uint64_t bucket(const detail::Level<D>& L, std::uint64_t key) const {
    if (L.ranked) {
      const std::uint64_t w = L.word_base + (key >> 6);
      const std::uint64_t bit = std::uint64_t{1} << (key & 63);
      const std::uint64_t word = words_[w];
      if (!(word & bit)) return detail::kNoBucket;
      return L.bucket_base + rank_[w] + static_cast<std::uint64_t>(std::popcount(word & (bit - 1)));
    }
    const std::uint64_t mask = L.buckets - 1;
    std::uint64_t slot = detail::hash_key(key) >> L.shift;
    for (;;) {
      const std::uint64_t k = keys_[L.key_base + slot];
      if (k == key) return L.bucket_base + slot;
      if (k == detail::kEmptyKey) return detail::kNoBucket;
      slot = (slot + 1) & mask;
    }
  }
  std::uint64_t insert_key(detail::Level<D>& L, std::uint64_t key) {
    const std::uint64_t mask = L.buckets - 1;
    std::uint64_t slot = detail::hash_key(key) >> L.shift;
    for (;;) {
      std::uint64_t& k = keys_[L.key_base + slot];
      if (k == key) return L.bucket_base + slot;
      if (k == detail::kEmptyKey) {
        k = key;
        return L.bucket_base + slot;
      }
      slot = (slot + 1) & mask;
    }
  }
  /// Calls f(bucket, cell key) for every non-empty cell of level L, in bucket order.
  template <class F>
  void for_each_cell(const detail::Level<D>& L, F&& f) const {
    if (L.ranked) {
      std::uint64_t b = L.bucket_base;
      for (std::uint64_t w = 0; w < L.words; ++w)
        for (std::uint64_t bits = words_[L.word_base + w]; bits; bits &= bits - 1)
          f(b++, (w << 6) | static_cast<std::uint64_t>(std::countr_zero(bits)));
      return;
    }
    for (std::uint64_t k = 0; k < L.buckets; ++k) {
      const std::uint64_t b = L.bucket_base + k;
      if (start_[b] != start_[b + 1]) f(b, keys_[L.key_base + k]);
    }
  }
  /// Calls g(bucket) for each non-empty cell with key in [key, key + len) of a ranked level.
  template <class G>
  void scan_row(const detail::Level<D>& L, std::uint64_t key, std::uint64_t len, G& g) const {
    const std::uint64_t end = key + len;
    for (std::uint64_t w = key >> 6; (w << 6) < end; ++w) {
      std::uint64_t bits = words_[L.word_base + w];
      const std::uint64_t lo = w << 6;
      if (key > lo) bits &= ~std::uint64_t{0} << (key - lo);
      if (end < lo + 64) bits &= (std::uint64_t{1} << (end - lo)) - 1;
      for (; bits; bits &= bits - 1) {
        const std::uint64_t below = words_[L.word_base + w] & ((bits & (~bits + 1)) - 1);
        g(L.bucket_base + rank_[L.word_base + w] + static_cast<std::uint64_t>(std::popcount(below)));
      }
    }
  }
  /// Content of the cell with the given coordinates at level L: [begin, end).
  std::pair<std::uint32_t, std::uint32_t> cell_range(const detail::Level<D>& L, const Coords& c) const {
    const std::uint64_t b = bucket(L, L.key(c));
    if (b == detail::kNoBucket) return {0, 0};
    return {start_[b], start_[b + 1]};
  }

  template <class Count, class F>
  void test(std::uint32_t p, std::uint32_t q, F& f, Counters& out) const {
    if (detail::overlap<D, B>(sorted_[p], sorted_[q], box_)) {
      const std::uint32_t i = id_[p], j = id_[q];
      if constexpr (Count::enabled) ++out.contacts;
      if (i < j) f(i, j); else f(j, i);
    }
  }

  template <class Count, class F>
  void cross_level(std::uint32_t p, int h, int j, F& f, Counters& out) const;

  GridParams params_;
  Extent<D> box_{};
  std::vector<detail::Level<D>> levels_;
  std::vector<Sphere<D>> sorted_;        // particles sorted by (level, cell)
  std::vector<std::uint32_t> id_;        // input index of each sorted particle
  std::vector<std::uint32_t> start_;     // bucket -> first sorted particle; one past the last bucket too
  std::vector<std::uint64_t> keys_;      // cell keys of the hashed levels' tables
  std::vector<std::uint64_t> words_;     // ranked levels: one bit per cell, set if non-empty
  std::vector<std::uint32_t> rank_;      // ranked levels: set bits before each word (within its level)
  std::vector<std::uint32_t> level_begin_;  // first sorted particle of each level, plus N
};

// ---------------------------------------------------------------------------

template <int D, Boundary B>
HGrid<D, B>::HGrid(std::span<const Sphere<D>> spheres, const Extent<D>& box, const GridParams& params)
    : params_(params), box_(box) {
  const auto& s = params_.sizes;
  if (s.empty()) throw InputError("sizes", "at least one cell size is needed (L >= 1)");
  for (std::size_t h = 0; h < s.size(); ++h) {
    if (!(std::isfinite(s[h]) && s[h] > 0))
      throw InputError("sizes", "s_" + std::to_string(h + 1) + " = " + std::to_string(s[h]) + " must be finite and > 0");
    if (h > 0 && !(s[h] > s[h - 1]))
      throw InputError("sizes", "must be strictly increasing (s_" + std::to_string(h + 1) + " = " +
                                    std::to_string(s[h]) + " <= s_" + std::to_string(h) + ")");
  }
  for (int a = 0; a < D; ++a)
    if (!(std::isfinite(box[a]) && box[a] > 0))
      throw InputError("box", "side " + std::to_string(a + 1) + " must be finite and > 0");
  if (spheres.size() >= (std::size_t{1} << 31))
    throw InputError("n", "at most 2^31 - 1 particles per grid");

  const std::size_t N = spheres.size();
  sorted_.resize(N);
  id_.resize(N);
  double d_max = 0;
  for (std::size_t i = 0; i < N; ++i) {
    const auto& p = spheres[i];
    if (!(std::isfinite(p.r) && p.r > 0))
      throw InputError("radius", "particle " + std::to_string(i) + " has radius " + std::to_string(p.r) +
                                     " (must be finite and > 0)");
    for (int a = 0; a < D; ++a) {
      if (!std::isfinite(p.x[a]))
        throw InputError("position", "particle " + std::to_string(i) + " has a non-finite coordinate");
      if (B == Boundary::walls && (p.x[a] < 0 || p.x[a] > box[a]))
        throw InputError("position", "particle " + std::to_string(i) + " has its centre outside the walled box [0, " +
                                         std::to_string(box[a]) + "] on axis " + std::to_string(a + 1));
    }
    d_max = std::max(d_max, 2 * p.r);
  }
  if (N > 0 && d_max > s.back())
    throw InputError("sizes", "the last cell size " + std::to_string(s.back()) +
                                  " is below the largest diameter " + std::to_string(d_max));

  levels_ = detail::make_levels<D>(s, box, B);
  const int L = levels();

  // Pass 1: level of insertion (the effective sizes never decrease with h).
  std::vector<std::uint32_t> tag(N);  // level, then bucket
  std::vector<std::uint64_t> per_level(L, 0);
  for (std::size_t i = 0; i < N; ++i) {
    const double d = 2 * spheres[i].r;
    int h = 0;
    while (h < L - 1 && d > levels_[h].s_min) ++h;
    tag[i] = static_cast<std::uint32_t>(h);
    ++per_level[h];
  }
  // Directory layout: a rank directory per level, or a hash table if very sparse.
  std::uint64_t words = 0, keys = 0;
  for (int h = 0; h < L; ++h) {
    auto& lv = levels_[h];
    const std::uint64_t cells = lv.cells();
    lv.ranked = cells <= detail::kRankCellsPerParticle * per_level[h] + detail::kRankMinCells;
    if (lv.ranked) {
      lv.word_base = words;
      lv.words = (cells + 63) / 64;
      words += lv.words;
    } else {
      std::uint64_t size = 16;
      int bits = 4;
      while (size < 2 * per_level[h]) size <<= 1, ++bits;
      lv.buckets = size;
      lv.shift = 64 - bits;
      lv.key_base = keys;
      keys += size;
    }
  }
  words_.assign(words, 0);
  keys_.assign(keys, detail::kEmptyKey);

  // Pass 2: cell of each particle; occupied bits / hash keys.
  auto wrapped = [&](std::size_t i) {
    Sphere<D> p = spheres[i];
    if constexpr (B == Boundary::periodic) {
      for (int a = 0; a < D; ++a) p.x[a] = detail::wrap(p.x[a], box[a]);
    }
    return p;
  };
  std::vector<std::uint64_t> cell_key(N);
  for (std::size_t i = 0; i < N; ++i) {
    auto& lv = levels_[tag[i]];
    cell_key[i] = lv.key(lv.cell(wrapped(i).x));
    if (lv.ranked) words_[lv.word_base + (cell_key[i] >> 6)] |= std::uint64_t{1} << (cell_key[i] & 63);
  }
  // Ranks, then bucket bases: ranked levels have one bucket per non-empty cell.
  rank_.assign(words, 0);
  std::uint64_t buckets = 0;
  for (int h = 0; h < L; ++h) {
    auto& lv = levels_[h];
    lv.bucket_base = buckets;
    if (lv.ranked) {
      std::uint32_t r = 0;
      for (std::uint64_t w = 0; w < lv.words; ++w) {
        rank_[lv.word_base + w] = r;
        r += static_cast<std::uint32_t>(std::popcount(words_[lv.word_base + w]));
      }
      lv.buckets = r;
    }
    buckets += lv.buckets;
  }
  if (buckets >= (std::uint64_t{1} << 32) - 1) throw InputError("sizes", "too many cells for one grid");
  // Counting sort of the particles into buckets (stable: input order within a cell).
  std::vector<std::uint32_t> count(buckets + 1, 0);
  for (std::size_t i = 0; i < N; ++i) {
    auto& lv = levels_[tag[i]];
    const std::uint64_t b = lv.ranked ? bucket(lv, cell_key[i]) : insert_key(lv, cell_key[i]);
    tag[i] = static_cast<std::uint32_t>(b);
    ++count[b + 1];
  }
  cell_key = {};
  for (std::uint64_t b = 0; b < buckets; ++b) count[b + 1] += count[b];
  start_ = count;  // start_[b] = first particle of bucket b; start_[buckets] = N
  // Scatter the 4-byte ids, then gather the spheres in sorted order: random
  // reads overlap in the memory system far better than random 32-byte writes.
  // Both loops are bound by memory latency: fetch a few iterations ahead.
  constexpr std::size_t ahead = 16;
  for (std::size_t i = 0; i < N; ++i) {
    if (i + ahead < N) __builtin_prefetch(&count[tag[i + ahead]], 1);
    id_[count[tag[i]]++] = static_cast<std::uint32_t>(i);
  }
  for (std::size_t k = 0; k < N; ++k) {
    if (k + ahead < N) __builtin_prefetch(&spheres[id_[k + ahead]]);
    sorted_[k] = wrapped(id_[k]);
  }
  level_begin_.resize(L + 1);
  for (int h = 0; h < L; ++h) level_begin_[h] = start_[levels_[h].bucket_base];
  level_begin_[L] = static_cast<std::uint32_t>(N);
}

template <int D, Boundary B>
template <class Count, class F>
void HGrid<D, B>::cross_level(std::uint32_t p, int h, int j, F& f, Counters& out) const {
  const auto& lv = levels_[j];
  const Sphere<D>& sp = sorted_[p];
  // Search box x_p +- beta, beta = r_p + s_j / 2 (Eq. 4), as cell ranges.
  std::array<std::int64_t, D> lo{}, hi{};
  std::array<bool, D> wrap{};
  for (int a = 0; a < D; ++a) {
    const double beta = sp.r + 0.5 * lv.s[a];
    const double n = static_cast<double>(lv.n[a]);
    double l = std::floor((sp.x[a] - beta) / lv.s[a]);
    double u = std::floor((sp.x[a] + beta) / lv.s[a]);
    if constexpr (B == Boundary::walls) {
      l = std::clamp(l, 0.0, n - 1);  // cells beyond a wall do not exist
      u = std::clamp(u, 0.0, n - 1);
      wrap[a] = false;
    } else if (u - l + 1 >= n) {  // the box covers the whole periodic axis: each cell once
      l = 0;
      u = n - 1;
      wrap[a] = false;
    } else {
      wrap[a] = true;
    }
    lo[a] = static_cast<std::int64_t>(l);
    hi[a] = static_cast<std::int64_t>(u);
  }
  std::uint64_t accessed = 1, checked = 0;
  for (int a = 0; a < D; ++a) accessed *= static_cast<std::uint64_t>(hi[a] - lo[a] + 1);
  const std::uint32_t first = level_begin_[j], last = level_begin_[j + 1];
  if (accessed > last - first) {
    // The box holds more cells than level j holds particles: visit the
    // particles and keep those whose cell is in the box. Same pairs, same
    // counts (every cell of the box still counts as one access), less work.
    for (std::uint32_t q = first; q < last; ++q) {
      bool inside = true;
      for (int a = 0; a < D && inside; ++a) {
        std::int64_t k = lv.cell_1d(sorted_[q].x[a], a) - lo[a];
        if (wrap[a]) {  // the unwrapped range [lo, hi] is narrower than n: one image can match
          k %= lv.n[a];
          if (k < 0) k += lv.n[a];
        }
        inside = k >= 0 && k <= hi[a] - lo[a];
      }
      if (!inside) continue;
      ++checked;
      test<Count>(p, q, f, out);
    }
  } else if (lv.ranked) {
    // Rows along axis 0 are runs of consecutive keys: read the occupancy bits
    // a word at a time and visit only the non-empty cells (an empty cell adds
    // an access, counted above, and nothing else).
    auto visit = [&](std::uint64_t b) {
      const std::uint32_t qb = start_[b], qe = start_[b + 1];
      checked += qe - qb;
      for (std::uint32_t q = qb; q < qe; ++q) test<Count>(p, q, f, out);
    };
    const std::int64_t n0 = lv.n[0];
    Coords c = lo;
    for (;;) {
      Coords w = c;
      w[0] = 0;
      if constexpr (B == Boundary::periodic) {
        for (int a = 1; a < D; ++a)
          if (wrap[a]) w[a] = c[a] < 0 ? c[a] + lv.n[a] : (c[a] >= lv.n[a] ? c[a] - lv.n[a] : c[a]);
      }
      const std::uint64_t row = lv.key(w);
      if (lo[0] < 0) {  // only with wrap: [lo, hi] = [n + lo, n) + [0, hi]
        scan_row(lv, row + static_cast<std::uint64_t>(n0 + lo[0]), static_cast<std::uint64_t>(-lo[0]), visit);
        scan_row(lv, row, static_cast<std::uint64_t>(hi[0] + 1), visit);
      } else if (hi[0] >= n0) {
        scan_row(lv, row + static_cast<std::uint64_t>(lo[0]), static_cast<std::uint64_t>(n0 - lo[0]), visit);
        scan_row(lv, row, static_cast<std::uint64_t>(hi[0] - n0 + 1), visit);
      } else {
        scan_row(lv, row + static_cast<std::uint64_t>(lo[0]), static_cast<std::uint64_t>(hi[0] - lo[0] + 1), visit);
      }
      int a = 1;
      for (; a < D; ++a) {
        if (++c[a] <= hi[a]) break;
        c[a] = lo[a];
      }
      if (a == D) break;
    }
  } else {
    Coords c = lo;
    for (;;) {
      Coords w = c;
      if constexpr (B == Boundary::periodic) {
        for (int a = 0; a < D; ++a)
          if (wrap[a]) w[a] = c[a] < 0 ? c[a] + lv.n[a] : (c[a] >= lv.n[a] ? c[a] - lv.n[a] : c[a]);
      }
      const auto [b, e] = cell_range(lv, w);
      checked += e - b;
      for (std::uint32_t q = b; q < e; ++q) test<Count>(p, q, f, out);
      int a = 0;
      for (; a < D; ++a) {
        if (++c[a] <= hi[a]) break;
        c[a] = lo[a];
      }
      if (a == D) break;
    }
  }
  if constexpr (Count::enabled) {
    const int L = levels();
    out.cell_accesses += accessed;
    out.narrow_phase_checks += checked;
    out.accesses_by_level[h * L + j] += accessed;
    out.checks_by_level[h * L + j] += checked;
  }
}

template <int D, Boundary B>
template <Search S, class Count, class F>
Counters HGrid<D, B>::query(F&& f) const {
  const int L = levels();
  Counters out;
  out.levels = L;
  out.particles_per_level = particles_per_level();
  if constexpr (Count::enabled) {
    out.accesses_by_level.assign(L * L, 0);
    out.checks_by_level.assign(L * L, 0);
  }
  std::array<std::pair<std::uint32_t, std::uint32_t>, detail::kHalfStencil<D>> nb;
  for (int h = 0; h < L; ++h) {
    const auto& lv = levels_[h];
    detail::KeyWalk<D> walk(lv);
    for_each_cell(lv, [&](std::uint64_t b, std::uint64_t key) {
      const std::uint32_t beg = start_[b], end = start_[b + 1];
      // Same level (linked cell): the half stencil is shared by the cell's particles.
      const Coords& c = walk.to(key);
      int n_nb = 0;
      std::uint64_t nb_particles = 0;
      detail::for_each_half_neighbour<D, B>(lv, c, [&](const Coords& nc) {
        nb[n_nb] = cell_range(lv, nc);
        nb_particles += nb[n_nb].second - nb[n_nb].first;
        ++n_nb;
      });
      for (std::uint32_t p = beg; p < end; ++p) {
        for (std::uint32_t q = p + 1; q < end; ++q) test<Count>(p, q, f, out);
        for (int m = 0; m < n_nb; ++m)
          for (std::uint32_t q = nb[m].first; q < nb[m].second; ++q) test<Count>(p, q, f, out);
        if constexpr (Count::enabled) {
          const std::uint64_t acc = 1 + static_cast<std::uint64_t>(n_nb);
          const std::uint64_t chk = (end - p - 1) + nb_particles;
          out.cell_accesses += acc;
          out.narrow_phase_checks += chk;
          out.accesses_by_level[h * L + h] += acc;
          out.checks_by_level[h * L + h] += chk;
        }
        // Cross-level search (Eqs. 4-5): lower levels (Top-Down) or higher ones (Bottom-Up).
        if constexpr (S == Search::top_down) {
          for (int j = 0; j < h; ++j) cross_level<Count>(p, h, j, f, out);
        } else {
          for (int j = h + 1; j < L; ++j) cross_level<Count>(p, h, j, f, out);
        }
      }
    });
  }
  return out;
}

}  // namespace hgrid
