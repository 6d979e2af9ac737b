// HGrid construction: level of insertion and cell of every particle, then a
// stable sort by (level, cell key) in two cache-friendly steps, and the flat
// cell directory. Included by hgrid/hgrid.hpp only.
#pragma once
#include <bit>
#include <string>
#include <vector>

#include "grid/detail/radix.hpp"

namespace hgrid {

template <int D, Boundary B>
HGrid<D, B>::HGrid(std::span<const Sphere<D>> spheres, const Extent<D>& box, const GridParams& params)
    : params_(params), box_(box) {
  const auto& s = params_.sizes;
  if (s.empty()) throw InputError("sizes", "at least one cell size is needed (L >= 1)");
  if (s.size() > static_cast<std::size_t>(kMaxLevels))
    throw InputError("sizes", "at most " + std::to_string(kMaxLevels) + " levels (got " + std::to_string(s.size()) + ")");
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
  levels_ = detail::make_levels<D>(s, box, B);
  Scratch scratch;  // released on return: a grid only constructed keeps no workspace
  build(spheres, scratch);
}

template <int D, Boundary B>
void HGrid<D, B>::rebuild(std::span<const Sphere<D>> spheres) {
  build(spheres, scratch_);
}

template <int D, Boundary B>
void HGrid<D, B>::build(std::span<const Sphere<D>> spheres, Scratch& ws) {
  const std::vector<double>& s = params_.sizes;
  const Extent<D>& box = box_;
  const std::size_t N = spheres.size();
  if (N >= (std::size_t{1} << 31)) throw InputError("n", "at most 2^31 - 1 particles per grid");
  const int L = levels();
  const auto wrapped = [&](std::size_t i) {
    Sphere<D> p = spheres[i];
    if constexpr (B == Boundary::periodic) {
      for (int a = 0; a < D; ++a) p.x[a] = detail::wrap(p.x[a], box[a]);
    }
    return p;
  };

  // The sort by (level, cell key) runs in two steps, so that neither makes
  // random accesses over all N particles (which is what bounds a gather or a
  // full-range scatter by memory latency): a counting sort into coarse
  // buckets, each one level's run of 2^shift consecutive keys, that moves the
  // particles themselves (sequential reads, a few hundred write streams);
  // then, inside each bucket, which fits in the cache, a radix sort of the
  // low key bits and the permutation of its particles. Both steps are stable.
  auto& shift = ws.shift;
  auto& coarse_base = ws.coarse_base;
  shift.assign(L, 0);
  coarse_base.assign(L + 1, 0);
  for (int h = 0; h < L; ++h) {
    const LevelSortWork w = level_sort_work(levels_[h].cells(), N);
    shift[h] = w.shift;
    coarse_base[h + 1] = coarse_base[h] + static_cast<std::uint32_t>(w.buckets);
  }
  // Cell key (Eq. 1) on its level of insertion, and coarse bucket, of a
  // (wrapped) particle.
  struct Place {
    std::uint64_t key;
    std::uint32_t coarse;
  };
  const auto place = [&](const Sphere<D>& p) {
    const int h = insertion_level(p.r);
    const std::uint64_t k = levels_[h].key(levels_[h].cell(p.x));
    return Place{k, coarse_base[h] + static_cast<std::uint32_t>(k >> shift[h])};
  };

  // Pass 1: check every particle, find its place, count the particles per
  // coarse bucket.
  // Nothing of the grid itself changes before every particle has passed its
  // checks: a rejected input leaves the grid as it was.
  auto& cursor = ws.cursor;
  cursor.assign(coarse_base[L] + 1, 0);
  ws.key_in.resize(N);  // uninitialised, all written
  ws.coarse.resize(N);
  std::uint64_t* const key_in = ws.key_in.data();
  std::uint32_t* const coarse = ws.coarse.data();
  double d_max = 0;
  for (std::size_t i = 0; i < N; ++i) {
    const auto& q = spheres[i];
    if (!(std::isfinite(q.r) && q.r > 0))
      throw InputError("radius", "particle " + std::to_string(i) + " has radius " + std::to_string(q.r) +
                                     " (must be finite and > 0)");
    for (int a = 0; a < D; ++a) {
      if (!std::isfinite(q.x[a]))
        throw InputError("position", "particle " + std::to_string(i) + " has a non-finite coordinate");
      if (B == Boundary::walls && (q.x[a] < 0 || q.x[a] > box[a]))
        throw InputError("position", "particle " + std::to_string(i) + " has its centre outside the walled box [0, " +
                                         std::to_string(box[a]) + "] on axis " + std::to_string(a + 1));
    }
    d_max = std::max(d_max, 2 * q.r);
    const Place pl = place(wrapped(i));
    key_in[i] = pl.key;
    coarse[i] = pl.coarse;
    ++cursor[pl.coarse + 1];
  }
  if (N > 0 && d_max > s.back())
    throw InputError("sizes", "the last cell size " + std::to_string(s.back()) +
                                  " is below the largest diameter " + std::to_string(d_max));
  for (std::size_t c = 1; c < cursor.size(); ++c) cursor[c] += cursor[c - 1];
  ws.bucket_begin.assign(cursor.begin(), cursor.end());
  const auto& bucket_begin = ws.bucket_begin;
  level_begin_.resize(L + 1);
  for (int h = 0; h <= L; ++h) level_begin_[h] = bucket_begin[coarse_base[h]];

  // Pass 2: move every particle into its coarse bucket.
  ws.key.resize(N);
  std::uint64_t* const key = ws.key.data();
  id_.resize(N);
  sorted_.resize(N);
  for (std::size_t i = 0; i < N; ++i) {
    const std::uint32_t at = cursor[coarse[i]]++;
    sorted_[at] = wrapped(i);
    key[at] = key_in[i];
    id_[at] = static_cast<std::uint32_t>(i);
  }

  // The directory's layout per level, from the particle counts: a rank
  // directory (one bit per cell, a prefix count per 64 cells), or an
  // open-addressing table of keys if the level is very sparse.
  std::uint64_t words = 0, slots = 0;
  for (int h = 0; h < L; ++h) {
    auto& lv = levels_[h];
    const std::uint64_t n_h = level_begin_[h + 1] - level_begin_[h];
    lv.ranked = lv.cells() <= detail::kRankCellsPerParticle * n_h + detail::kRankMinCells;
    lv.word_base = lv.words = lv.slots = lv.key_base = 0;  // the previous build's layout, if any
    lv.shift = 64;
    if (lv.ranked) {
      lv.word_base = words;
      lv.words = lv.cells() / 64 + 1;
      words += lv.words;
    } else {
      std::uint64_t size = 16;
      int bits = 4;
      while (size < 2 * n_h) size <<= 1, ++bits;  // at most n_h non-empty cells
      lv.slots = size;
      lv.shift = 64 - bits;
      lv.key_base = slots;
      slots += size;
    }
  }
  words_.assign(words, 0);
  rank_.resize(words);
  keys_.assign(slots, detail::kEmptyKey);
  slot_bucket_.assign(slots, 0);
  start_.resize(N + 1);  // at most one bucket per particle; trimmed below

  // Pass 3: inside each coarse bucket, sort by the low key bits and permute;
  // then, while the bucket is in the cache, one directory bucket per
  // non-empty cell, in (level, key) order.
  std::uint64_t buckets = 0;
  {
    std::size_t most = 0;
    for (std::size_t c = 0; c + 1 < bucket_begin.size(); ++c)
      most = std::max<std::size_t>(most, bucket_begin[c + 1] - bucket_begin[c]);
    auto& tkey = ws.tkey;
    auto &order = ws.order, &torder = ws.torder, &tid = ws.tid;
    auto& tsph = ws.tsph;
    for (auto* v : {&order, &torder, &tid}) v->resize(most);
    tkey.resize(most);
    tsph.resize(most);
    for (int h = 0; h < L; ++h) {
      auto& lv = levels_[h];
      lv.bucket_base = buckets;
      for (std::uint32_t c = coarse_base[h]; c < coarse_base[h + 1]; ++c) {
        const std::uint32_t b = bucket_begin[c], n = bucket_begin[c + 1] - b;
        const std::uint64_t* k = key + b;
        if (n >= 2) {
          // The permutation below reads the bucket's particles in random
          // order, and the scatter wrote them long ago (out of the cache at
          // large N): ask for all of them first, in address order, so that
          // the loads overlap with the key sort instead of each waiting for
          // memory (build at N = 10^6: about -1.5 ns/particle).
          for (std::uint32_t m = 0; m < n; m += 2) __builtin_prefetch(&sorted_[b + m]);
          for (std::uint32_t m = 0; m < n; m += 16) __builtin_prefetch(&id_[b + m]);
          for (std::uint32_t m = 0; m < n; ++m) order[m] = m;
          detail::radix_sort_pairs(key + b, order.data(), tkey.data(), torder.data(), n, shift[h]);
          for (std::uint32_t m = 0; m < n; ++m) {
            tsph[m] = sorted_[b + order[m]];
            tid[m] = id_[b + order[m]];
          }
          std::copy(tsph.begin(), tsph.begin() + n, sorted_.begin() + b);
          std::copy(tid.begin(), tid.begin() + n, id_.begin() + b);
        }
        for (std::uint32_t m = 0; m < n; ++m) {
          if (m > 0 && k[m] == k[m - 1]) continue;
          start_[buckets] = b + m;
          if (lv.ranked) {
            words_[lv.word_base + (k[m] >> 6)] |= std::uint64_t{1} << (k[m] & 63);
          } else {
            std::uint64_t slot = detail::hash_key(k[m]) >> lv.shift;
            while (keys_[lv.key_base + slot] != detail::kEmptyKey) slot = (slot + 1) & (lv.slots - 1);
            keys_[lv.key_base + slot] = k[m];
            slot_bucket_[lv.key_base + slot] = static_cast<std::uint32_t>(buckets - lv.bucket_base);
          }
          ++buckets;
        }
      }
      lv.buckets = buckets - lv.bucket_base;
      if (lv.ranked) {
        std::uint32_t r = 0;
        for (std::uint64_t w = 0; w < lv.words; ++w) {
          rank_[lv.word_base + w] = r;
          r += static_cast<std::uint32_t>(std::popcount(words_[lv.word_base + w]));
        }
      }
    }
  }
  start_[buckets] = static_cast<std::uint32_t>(N);
  start_.resize(buckets + 1);

  // The order of the Top-Down cross-level searches: the particles above the
  // lowest level, all levels interleaved, by the key of their cell on the
  // lowest level. The lowest level usually holds most particles; searching
  // it in its own cell order streams it through the cache about once,
  // instead of once per level above it.
  const std::size_t n_up = N - level_begin_[std::min(1, L)];
  sweep_.clear();
  if (L > 1 && n_up > 0) {
    auto &k0 = ws.k0, &tk = ws.tk;
    auto& t = ws.t;
    k0.resize(n_up);
    tk.resize(n_up);
    t.resize(n_up);
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
