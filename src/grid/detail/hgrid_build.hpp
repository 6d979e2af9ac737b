// HGrid construction: level of insertion and cell of every particle, then a
// stable sort by (level, cell key) in two cache-friendly steps, and the flat
// cell directory. Included by hgrid/hgrid.hpp only.
#pragma once
#include <atomic>
#include <bit>
#include <exception>
#include <string>
#include <vector>

#include "hgridlab/base/parallel.hpp"
#include "hgridlab/base/radix.hpp"

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
  detail::make_levels<D>(s, box, B, levels_);
  Scratch scratch;  // released on return: a grid only constructed keeps no workspace
  build(spheres, scratch);
}

template <int D, Boundary B>
void HGrid<D, B>::rebuild(std::span<const Sphere<D>> spheres) {
  build(spheres, scratch_);
}

template <int D, Boundary B>
void HGrid<D, B>::rebuild(std::span<const Sphere<D>> spheres, const Extent<D>& box) {
  detail::make_levels<D>(params_.sizes, box, B, scratch_.levels);  // checks the box; throws before any change
  std::swap(levels_, scratch_.levels);
  const Extent<D> old_box = box_;
  box_ = box;
  try {
    build(spheres, scratch_);  // changes nothing of the grid before the input has passed its checks
  } catch (...) {
    std::swap(levels_, scratch_.levels);
    box_ = old_box;
    throw;
  }
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
    const LevelSortWork w = level_sort_work(levels_[h].cells(), N, L);
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

  // The passes below run on T threads: pass 1 and 2 on T contiguous blocks
  // of the input (each thread counts, then scatters, its own block, so the
  // sort stays stable), pass 3 on the coarse buckets, handed out one at a
  // time. The grid is the same for any T.
  const int T = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(resolve_threads(params_.threads)),
                                                       std::max<std::size_t>(1, N / kMinParticlesPerThread)));
  const std::size_t C = coarse_base[L];  // coarse buckets
  const auto block = [&](int t) {
    return std::pair<std::size_t, std::size_t>{N * static_cast<std::size_t>(t) / static_cast<std::size_t>(T),
                                               N * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(T)};
  };

  // Pass 1: check every particle, find its place, count the particles per
  // coarse bucket (per thread).
  // Nothing of the grid itself changes before every particle has passed its
  // checks: a rejected input leaves the grid as it was; the error reported
  // is the one of the lowest index, as on one thread.
  auto& cursor = ws.cursor;  // T rows of C + 1 counts, then of write positions
  cursor.assign(static_cast<std::size_t>(T) * (C + 1), 0);
  ws.key_in.resize(N);  // uninitialised, all written
  ws.coarse.resize(N);
  std::uint64_t* const key_in = ws.key_in.data();
  std::uint32_t* const coarse = ws.coarse.data();
  auto& d_max_of = ws.d_max_of;
  auto& error_of = ws.error_of;
  d_max_of.assign(static_cast<std::size_t>(T), 0.0);
  error_of.assign(static_cast<std::size_t>(T), nullptr);
  detail::parallel_for(T, T, [&](std::size_t t, int) {
    const auto [i0, i1] = block(static_cast<int>(t));
    std::uint32_t* const count = cursor.data() + t * (C + 1);
    double d_max = 0;
    try {
      for (std::size_t i = i0; i < i1; ++i) {
        const auto& q = spheres[i];
        if (!(std::isfinite(q.r) && q.r > 0))
          throw InputError("radius", "particle " + std::to_string(i) + " has radius " + std::to_string(q.r) +
                                         " (must be finite and > 0)");
        for (int a = 0; a < D; ++a) {
          if (!std::isfinite(q.x[a]))
            throw InputError("position", "particle " + std::to_string(i) + " has a non-finite coordinate");
          if (B == Boundary::walls && (q.x[a] < 0 || q.x[a] > box[a]))
            throw InputError("position", "particle " + std::to_string(i) +
                                             " has its centre outside the walled box [0, " + std::to_string(box[a]) +
                                             "] on axis " + std::to_string(a + 1));
        }
        d_max = std::max(d_max, 2 * q.r);
        const Place pl = place(wrapped(i));
        key_in[i] = pl.key;
        coarse[i] = pl.coarse;
        ++count[pl.coarse];
      }
    } catch (...) {
      error_of[t] = std::current_exception();  // blocks are in index order: the first one set is the lowest index
    }
    d_max_of[t] = d_max;
  });
  for (const auto& e : error_of)
    if (e) std::rethrow_exception(e);
  const double d_max = *std::max_element(d_max_of.begin(), d_max_of.end());
  if (N > 0 && d_max > s.back())
    throw InputError("sizes", "the last cell size " + std::to_string(s.back()) +
                                  " is below the largest diameter " + std::to_string(d_max));
  // Counts -> write positions: bucket c of thread t starts after bucket c of
  // the threads before t and after every bucket before c.
  ws.bucket_begin.resize(C + 1);
  {
    std::uint32_t at = 0;
    for (std::size_t c = 0; c < C; ++c) {
      ws.bucket_begin[c] = at;
      for (int t = 0; t < T; ++t) {
        std::uint32_t& v = cursor[static_cast<std::size_t>(t) * (C + 1) + c];
        const std::uint32_t n = v;
        v = at;
        at += n;
      }
    }
    ws.bucket_begin[C] = at;
  }
  const auto& bucket_begin = ws.bucket_begin;
  level_begin_.resize(L + 1);
  for (int h = 0; h <= L; ++h) level_begin_[h] = bucket_begin[coarse_base[h]];

  // Pass 2: move every particle into its coarse bucket.
  ws.key.resize(N);
  std::uint64_t* const key = ws.key.data();
  id_.resize(N);
  sorted_.resize(N);
  detail::parallel_for(T, T, [&](std::size_t t, int) {
    const auto [i0, i1] = block(static_cast<int>(t));
    std::uint32_t* const cur = cursor.data() + t * (C + 1);
    for (std::size_t i = i0; i < i1; ++i) {
      const std::uint32_t at = cur[coarse[i]]++;
      sorted_[at] = wrapped(i);
      key[at] = key_in[i];
      id_[at] = static_cast<std::uint32_t>(i);
    }
  });

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

  // Pass 3: inside each coarse bucket, sort by the low key bits and permute,
  // and count its distinct keys (its non-empty cells, one directory bucket
  // each); then, once every bucket knows where its directory buckets start,
  // fill the directory, buckets in (level, key) order.
  auto& level_of = ws.level_of;
  level_of.resize(C);
  for (int h = 0; h < L; ++h)
    for (std::uint32_t c = coarse_base[h]; c < coarse_base[h + 1]; ++c) level_of[c] = h;
  auto& cells_before = ws.cells_before;  // distinct keys of each coarse bucket, then their prefix sum
  cells_before.assign(C + 1, 0);
  // A bucket of one key (shift 0: a level sorted by one counting sort over
  // its cells, grid/build_work.hpp) is in order already and holds one cell
  // if it is not empty; only the others are sorted, on T threads.
  auto& sorting = ws.sorting;
  sorting.clear();
  for (int h = 0; h < L; ++h)
    for (std::uint32_t c = coarse_base[h]; c < coarse_base[h + 1]; ++c) {
      if (shift[h] > 0) sorting.push_back(c);
      else cells_before[c + 1] = bucket_begin[c + 1] != bucket_begin[c];
    }
  {
    std::size_t most = 0;
    for (const std::uint32_t c : sorting) most = std::max<std::size_t>(most, bucket_begin[c + 1] - bucket_begin[c]);
    auto& tkey = ws.tkey;
    auto &order = ws.order, &torder = ws.torder, &tid = ws.tid;
    auto& tsph = ws.tsph;
    const std::size_t per = most, all = per * static_cast<std::size_t>(T);  // one slice per thread
    for (auto* v : {&order, &torder, &tid}) v->resize(all);
    tkey.resize(all);
    tsph.resize(all);
    detail::parallel_for(T, sorting.size(), [&](std::size_t u, int t) {
      const std::uint32_t c = sorting[u];
      const std::size_t o = per * static_cast<std::size_t>(t);
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
        std::uint32_t* const ord = order.data() + o;
        for (std::uint32_t m = 0; m < n; ++m) ord[m] = m;
        detail::radix_sort_pairs(key + b, ord, tkey.data() + o, torder.data() + o, n, shift[level_of[c]]);
        for (std::uint32_t m = 0; m < n; ++m) {
          tsph[o + m] = sorted_[b + ord[m]];
          tid[o + m] = id_[b + ord[m]];
        }
        std::copy(tsph.begin() + o, tsph.begin() + o + n, sorted_.begin() + b);
        std::copy(tid.begin() + o, tid.begin() + o + n, id_.begin() + b);
      }
      std::uint32_t distinct = 0;
      for (std::uint32_t m = 0; m < n; ++m) distinct += m == 0 || k[m] != k[m - 1];
      cells_before[c + 1] = distinct;
    });
  }
  for (std::size_t c = 0; c < C; ++c) cells_before[c + 1] += cells_before[c];
  for (int h = 0; h < L; ++h) {
    levels_[h].bucket_base = cells_before[coarse_base[h]];
    levels_[h].buckets = cells_before[coarse_base[h + 1]] - cells_before[coarse_base[h]];
  }
  detail::parallel_for(T, sorting.size(), [&](std::size_t u, int) {
    const std::uint32_t c = sorting[u];
    const auto& lv = levels_[level_of[c]];
    const std::uint32_t b = bucket_begin[c], n = bucket_begin[c + 1] - b;
    const std::uint64_t* k = key + b;
    // Two coarse buckets share a bitmap word only if they hold fewer than
    // 64 keys each (shift < 6): then the word is set atomically.
    const bool shared = T > 1 && shift[level_of[c]] < 6;
    std::uint64_t bucket = cells_before[c];
    for (std::uint32_t m = 0; m < n; ++m) {
      if (m > 0 && k[m] == k[m - 1]) continue;
      start_[bucket] = b + m;
      if (lv.ranked) {
        const std::uint64_t bit = std::uint64_t{1} << (k[m] & 63);
        std::uint64_t& w = words_[lv.word_base + (k[m] >> 6)];
        if (shared) std::atomic_ref<std::uint64_t>(w).fetch_or(bit, std::memory_order_relaxed);
        else w |= bit;
      }
      ++bucket;
    }
  });
  // The buckets of one key, on one thread (their levels' words are their own).
  for (int h = 0; h < L; ++h) {
    if (shift[h] > 0) continue;
    const auto& lv = levels_[h];
    for (std::uint32_t c = coarse_base[h]; c < coarse_base[h + 1]; ++c) {
      if (bucket_begin[c + 1] == bucket_begin[c]) continue;
      start_[cells_before[c]] = bucket_begin[c];
      if (lv.ranked) {
        const std::uint64_t k = key[bucket_begin[c]];
        words_[lv.word_base + (k >> 6)] |= std::uint64_t{1} << (k & 63);
      }
    }
  }
  // The hashed levels' tables, on one thread (a level's coarse buckets would
  // share its table), in the same order as the buckets.
  for (int h = 0; h < L; ++h) {
    const auto& lv = levels_[h];
    if (lv.ranked) continue;
    std::uint64_t bucket = 0;
    for (std::uint32_t c = coarse_base[h]; c < coarse_base[h + 1]; ++c) {
      const std::uint32_t b = bucket_begin[c], n = bucket_begin[c + 1] - b;
      const std::uint64_t* k = key + b;
      for (std::uint32_t m = 0; m < n; ++m) {
        if (m > 0 && k[m] == k[m - 1]) continue;
        std::uint64_t slot = detail::hash_key(k[m]) >> lv.shift;
        while (keys_[lv.key_base + slot] != detail::kEmptyKey) slot = (slot + 1) & (lv.slots - 1);
        keys_[lv.key_base + slot] = k[m];
        slot_bucket_[lv.key_base + slot] = static_cast<std::uint32_t>(bucket++);
      }
    }
  }
  for (int h = 0; h < L; ++h) {
    const auto& lv = levels_[h];
    if (!lv.ranked) continue;
    std::uint32_t r = 0;
    for (std::uint64_t w = 0; w < lv.words; ++w) {
      rank_[lv.word_base + w] = r;
      r += static_cast<std::uint32_t>(std::popcount(words_[lv.word_base + w]));
    }
  }
  const std::uint64_t buckets = cells_before[C];
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
