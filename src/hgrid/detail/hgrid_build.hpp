// HGrid construction: level of insertion and cell of every particle, then a
// stable sort by (level, cell key) and the flat cell directory. Included by
// hgrid/hgrid.hpp only.
#pragma once
#include <bit>
#include <string>
#include <vector>

#include "hgrid/detail/radix.hpp"

namespace hgrid {

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
  const std::size_t N = spheres.size();
  if (N >= (std::size_t{1} << 31)) throw InputError("n", "at most 2^31 - 1 particles per grid");
  levels_ = detail::make_levels<D>(s, box, B);
  const int L = levels();
  const auto wrapped = [&](std::size_t i) {
    Sphere<D> p = spheres[i];
    if constexpr (B == Boundary::periodic) {
      for (int a = 0; a < D; ++a) p.x[a] = detail::wrap(p.x[a], box[a]);
    }
    return p;
  };
  // The level of insertion: the lowest h with 2 r <= s_h (Eq. 3); the
  // effective sizes never decrease with h.
  const auto level_of = [&](double r) {
    int h = 0;
    while (h < L - 1 && 2 * r > levels_[h].s_min) ++h;
    return h;
  };

  // Pass 1: check every particle and count the particles per level.
  level_begin_.assign(L + 1, 0);
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
    ++level_begin_[level_of(p.r) + 1];
  }
  if (N > 0 && d_max > s.back())
    throw InputError("sizes", "the last cell size " + std::to_string(s.back()) +
                                  " is below the largest diameter " + std::to_string(d_max));
  for (int h = 0; h < L; ++h) level_begin_[h + 1] += level_begin_[h];

  // Pass 2: cell key of every particle (Eq. 1), placed by level (a stable
  // counting sort), then sorted by key within each level (stable radix sort).
  std::vector<std::uint64_t> key(N), tkey(N);
  std::vector<std::uint32_t> tid(N);
  id_.resize(N);
  {
    std::vector<std::uint32_t> next(level_begin_.begin(), level_begin_.end() - 1);
    for (std::size_t i = 0; i < N; ++i) {
      const Sphere<D> p = wrapped(i);
      const int h = level_of(p.r);
      const std::uint32_t k = next[h]++;
      key[k] = levels_[h].key(levels_[h].cell(p.x));
      id_[k] = static_cast<std::uint32_t>(i);
    }
  }
  for (int h = 0; h < L; ++h) {
    const std::size_t b = level_begin_[h], n = level_begin_[h + 1] - b;
    const int bits = std::bit_width(levels_[h].cells() - 1);
    detail::radix_sort_pairs(key.data() + b, id_.data() + b, tkey.data(), tid.data(), n, bits);
  }
  tkey = {};
  tid = {};

  // Pass 3: the directory. One bucket per non-empty cell, in (level, key)
  // order; a rank directory per level (one bit per cell, a prefix count per
  // 64 cells), or an open-addressing table of keys if the level is very sparse.
  std::uint64_t words = 0, slots = 0, buckets = 0;
  for (int h = 0; h < L; ++h) {
    auto& lv = levels_[h];
    const std::uint64_t n_h = level_begin_[h + 1] - level_begin_[h];
    lv.buckets = 0;
    for (std::uint32_t k = level_begin_[h]; k < level_begin_[h + 1]; ++k)
      lv.buckets += k == level_begin_[h] || key[k] != key[k - 1];
    lv.bucket_base = buckets;
    buckets += lv.buckets;
    lv.ranked = lv.cells() <= detail::kRankCellsPerParticle * n_h + detail::kRankMinCells;
    if (lv.ranked) {
      lv.word_base = words;
      lv.words = lv.cells() / 64 + 1;
      words += lv.words;
    } else {
      std::uint64_t size = 16;
      int bits = 4;
      while (size < 2 * lv.buckets) size <<= 1, ++bits;
      lv.slots = size;
      lv.shift = 64 - bits;
      lv.key_base = slots;
      slots += size;
    }
  }
  if (buckets >= (std::uint64_t{1} << 32) - 1) throw InputError("sizes", "too many cells for one grid");
  words_.assign(words, 0);
  rank_.assign(words, 0);
  keys_.assign(slots, detail::kEmptyKey);
  slot_bucket_.assign(slots, 0);
  start_.resize(buckets + 1);
  for (int h = 0; h < L; ++h) {
    const auto& lv = levels_[h];
    std::uint64_t b = lv.bucket_base;
    for (std::uint32_t k = level_begin_[h]; k < level_begin_[h + 1]; ++k) {
      if (k != level_begin_[h] && key[k] == key[k - 1]) continue;
      start_[b] = k;
      if (lv.ranked) {
        words_[lv.word_base + (key[k] >> 6)] |= std::uint64_t{1} << (key[k] & 63);
      } else {
        std::uint64_t slot = detail::hash_key(key[k]) >> lv.shift;
        while (keys_[lv.key_base + slot] != detail::kEmptyKey) slot = (slot + 1) & (lv.slots - 1);
        keys_[lv.key_base + slot] = key[k];
        slot_bucket_[lv.key_base + slot] = static_cast<std::uint32_t>(b - lv.bucket_base);
      }
      ++b;
    }
    if (lv.ranked) {
      std::uint32_t r = 0;
      for (std::uint64_t w = 0; w < lv.words; ++w) {
        rank_[lv.word_base + w] = r;
        r += static_cast<std::uint32_t>(std::popcount(words_[lv.word_base + w]));
      }
    }
  }
  start_[buckets] = static_cast<std::uint32_t>(N);
  key = {};

  // Gather the particles in sorted order. Random reads bound by memory
  // latency: fetch a few iterations ahead.
  sorted_.resize(N);
  constexpr std::size_t ahead = 16;
  for (std::size_t k = 0; k < N; ++k) {
    if (k + ahead < N) __builtin_prefetch(&spheres[id_[k + ahead]]);
    sorted_[k] = wrapped(id_[k]);
  }

  // The order of the Top-Down cross-level searches: the particles above the
  // lowest level, all levels interleaved, by the key of their cell on the
  // lowest level. The lowest level usually holds most particles; searching
  // it in its own cell order streams it through the cache about once,
  // instead of once per level above it.
  const std::size_t n_up = N - level_begin_[std::min(1, L)];
  if (L > 1 && n_up > 0) {
    std::vector<std::uint64_t> k0(n_up), tk(n_up);
    std::vector<std::uint32_t> t(n_up);
    sweep_.resize(n_up);
    for (std::size_t i = 0; i < n_up; ++i) {
      sweep_[i] = static_cast<std::uint32_t>(level_begin_[1] + i);
      k0[i] = levels_[0].key(levels_[0].cell(sorted_[sweep_[i]].x));
    }
    detail::radix_sort_pairs(k0.data(), sweep_.data(), tk.data(), t.data(), n_up,
                             std::bit_width(levels_[0].cells() - 1));
  }
}

}  // namespace hgrid
