// HGrid queries: the same-level half stencil and the cross-level search
// (Krijgsman et al. 2014, Sect. 2, Eqs. 4-5). Included by hgrid/hgrid.hpp only.
#pragma once
#include <array>
#include <atomic>
#include <cmath>
#include <exception>
#include <type_traits>

namespace hgrid {

template <int D, Boundary B>
auto HGrid<D, B>::stencil_rows(const detail::Level<D>& L) const -> StencilRows {
  StencilRows out;
  if (L.ranked) out.dir = rank_view(L);
  out.valid = L.ranked && !(B == Boundary::periodic && L.small_periodic);
  out.plain_dx = B == Boundary::periodic;
  for (int a = 0; a < D; ++a) out.plain_dx = out.plain_dx && L.n[a] >= 5;
  static constexpr auto offsets = detail::half_offsets<D - 1>();
  for (std::size_t m = 0; m < offsets.size(); ++m) {
    std::int64_t dk = 0;  // key = ((c_0 n_1) + c_1) n_2 + c_2 in 3D
    for (int a = 0; a + 1 < D; ++a) dk = (dk + offsets[m][a]) * L.n[a + 1];
    out.delta[m] = dk;
  }
  return out;
}

template <int D, Boundary B>
template <class Add>
std::uint64_t HGrid<D, B>::half_stencil(const detail::Level<D>& L, const StencilRows& rows, const Coords& c,
                                        std::uint64_t key, std::uint64_t b, bool interior, Add&& add) const {
  // Interior cell: no row wraps or is clipped, so each row is the run of
  // keys key + delta - 1 .. + 1, and the own row's +1 cell starts right
  // after the own bucket.
  if (rows.valid && interior) {
    for (const std::int64_t dk : rows.delta) {
      const std::uint64_t k0 = key + static_cast<std::uint64_t>(dk) - 1;
      const auto [qb, qe] = rows.dir.run(k0, k0 + 3);
      add(qb, qe);  // possibly empty: no branch here
    }
    add(start_[b + 1], rows.dir.start[rows.dir.rank(key + 2)]);
    return detail::kHalfStencil<D>;
  }
  std::uint64_t cells = 0;
  if (!rows.valid) {  // hashed, or a periodic axis with fewer than 3 cells
    detail::for_each_half_neighbour<D, B>(L, c, [&](const Coords& nc) {
      const auto [b, e] = cell_range(L, nc);
      if (b != e) add(b, e);
      ++cells;
    });
    return cells;
  }
  // Ranked level with at least 3 cells per periodic axis: the half stencil
  // (offsets whose first non-zero component is +1) is, along the row axis
  // D-1, the full rows {-1, 0, 1} at the offsets u of the other axes whose
  // first non-zero component is +1, plus the cell +1 of the own row.
  const std::int64_t n = L.n[D - 1];
  auto runs = [&](std::uint64_t k0, std::uint64_t k1) {
    const auto [qb, qe] = rows.dir.run(k0, k1);
    add(qb, qe);  // possibly empty: no branch here
  };
  auto row = [&](const Coords& rc, std::int64_t lo, std::int64_t hi) {
    if constexpr (B == Boundary::walls) {
      lo = std::max<std::int64_t>(lo, 0);
      hi = std::min<std::int64_t>(hi, n - 1);
      if (lo > hi) return;
    }
    row_runs(L.key(rc), lo, hi, n, runs);
    cells += static_cast<std::uint64_t>(hi - lo + 1);
  };
  static constexpr auto offsets = detail::half_offsets<D - 1>();
  for (const auto& u : offsets) {
    Coords rc{};
    bool inside = true;
    for (int a = 0; a + 1 < D; ++a) {
      std::int64_t i = c[a] + u[a];
      if constexpr (B == Boundary::walls) {
        inside = inside && i >= 0 && i < L.n[a];
      } else {
        if (i < 0) i += L.n[a];
        if (i >= L.n[a]) i -= L.n[a];
      }
      rc[a] = i;
    }
    if (inside) row(rc, c[D - 1] - 1, c[D - 1] + 1);
  }
  Coords rc = c;
  rc[D - 1] = 0;
  row(rc, c[D - 1] + 1, c[D - 1] + 1);
  return cells;
}

template <int D, Boundary B>
template <class Count, class F>
void HGrid<D, B>::search_level(const Sphere<D>& sp, std::uint32_t p, int h, int j, F& f, Counters& out) const {
  const auto& lv = levels_[j];
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
  // A box inside the level (no wrap) is walked by a fixed key stride below.
  // Periodic: if it also spans less than half of every axis, every candidate
  // is nearer than A / 2 and the minimum image is the plain difference.
  bool inside = true, plain = B == Boundary::periodic;
  for (int a = 0; a < D; ++a) {
    inside = inside && lo[a] >= 0 && hi[a] < lv.n[a];
    plain = plain && 2 * (hi[a] - lo[a] + 1) < lv.n[a];
  }
  plain = plain && inside;
  auto range = [&](std::uint32_t qb, std::uint32_t qe) {
    checked += qe - qb;
    if constexpr (Count::enabled) out.runs += qe > qb;
    if (plain) test_range<Count, Boundary::walls>(sp, p, qb, qe, f, out);
    else test_range<Count>(sp, p, qb, qe, f, out);
  };
  const std::uint32_t first = level_begin_[j], last = level_begin_[j + 1];
  if constexpr (Count::enabled) {
    std::uint64_t rows = 1;  // the box's extent along every axis but the row axis D-1
    for (int a = 0; a + 1 < D; ++a) rows *= static_cast<std::uint64_t>(hi[a] - lo[a] + 1);
    const int L = levels();
    ++out.searches;
    ++out.searches_by_level[h * L + j];
    if (accessed > last - first) {
      out.scanned += last - first;
    } else if (!lv.ranked) {
      out.probes += accessed;
    } else {
      out.rows += rows;
      out.rows_by_level[h * L + j] += rows;
    }
  }
  if (accessed > last - first) {
    // The box holds more cells than level j holds particles: visit the
    // particles and keep those whose cell is in the box. Same pairs, same
    // counts (every cell of the box still counts as one access), less work.
    for (std::uint32_t q = first; q < last; ++q) {
      bool in_box = true;  // the cell of q lies in the box
      for (int a = 0; a < D && in_box; ++a) {
        std::int64_t k = lv.cell_1d(sorted_[q].x[a], a) - lo[a];
        if (wrap[a]) {  // the unwrapped range [lo, hi] is narrower than n: one image can match
          k %= lv.n[a];
          if (k < 0) k += lv.n[a];
        }
        in_box = k >= 0 && k <= hi[a] - lo[a];
      }
      if (!in_box) continue;
      ++checked;
      test<Count>(sp, p, q, f, out);
    }
  } else {
    // Walk the box a row (along axis D-1) at a time. On a ranked level a row
    // is one run of keys and its particles one contiguous range, whatever
    // the number of empty cells in it; otherwise look the cells up one by one.
    // The rows' ranges lie far apart in memory: gather a batch of them with
    // prefetches first, so that their cache misses overlap, then test. Most
    // rows hold 0 to 4 particles: their indices are appended to one list
    // without a data-dependent branch, so that the tests run as one loop
    // instead of one short, unpredictable loop per row.
    constexpr int kBatch = 32;
    std::array<std::uint32_t, kBatch> batch_b, batch_e;  // bucket ranks (within the level) of each row's ends
    std::array<std::uint32_t, kShortRange * (kBatch + 1)> cand;
    const RankView dir = rank_view(lv);
    int n_batch = 0;
    auto test_cand = [&](std::uint32_t n_cand) {
      checked += n_cand;
      if constexpr (Count::enabled) out.list_checks += n_cand;
      if (plain) test_list<Count, Boundary::walls>(sp, p, cand.data(), n_cand, f, out);
      else test_list<Count>(sp, p, cand.data(), n_cand, f, out);
    };
    auto flush = [&] {
      std::array<std::uint32_t, kBatch> qbs, qes;
      for (int i = 0; i < n_batch; ++i) {
        qbs[i] = dir.start[batch_b[i]];
        qes[i] = dir.start[batch_e[i]];
        __builtin_prefetch(&sorted_[qbs[i]]);
      }
      std::uint32_t n_cand = 0;
      for (int i = 0; i < n_batch; ++i)
        if (!append_short(cand, n_cand, qbs[i], qes[i])) range(qbs[i], qes[i]);
      test_cand(n_cand);
      n_batch = 0;
    };
    auto runs = [&](std::uint64_t k0, std::uint64_t k1) {
      const std::uint32_t b0 = dir.rank(k0), b1 = dir.rank(k1);
      __builtin_prefetch(&dir.start[b0]);
      batch_b[n_batch] = b0;
      batch_e[n_batch] = b1;
      n_batch += b0 != b1;  // rows of empty cells only are dropped, without a branch
      if (n_batch == kBatch) flush();
    };
    // A box inside a ranked level: its rows are runs of keys a fixed stride
    // apart, without wraps (the usual case).
    if (lv.ranked && inside) {
      const std::uint64_t len = static_cast<std::uint64_t>(hi[D - 1] - lo[D - 1] + 1);
      const std::uint64_t stride = static_cast<std::uint64_t>(lv.n[D - 1]);  // between rows along axis D-2
      const std::uint64_t rows = static_cast<std::uint64_t>(hi[D - 2] - lo[D - 2] + 1);
      const std::uint64_t planes = D == 3 ? static_cast<std::uint64_t>(hi[0] - lo[0] + 1) : 1;
      const std::uint64_t plane_stride = D == 3 ? stride * static_cast<std::uint64_t>(lv.n[D - 2]) : 0;
      const std::uint64_t k = lv.key(lo);
      auto each_row = [&](auto&& g) {  // g(first key of the row)
        for (std::uint64_t x = 0; x < planes; ++x)  // 3D: the planes along axis 0
          for (std::uint64_t m = 0; m < rows; ++m) g(k + x * plane_stride + m * stride);
      };
      if (rows * planes <= kBatch) {
        // A small box (most searches of the level just below): its rows'
        // ranges straight into the candidate list, without the batch.
        std::uint32_t n_cand = 0;
        each_row([&](std::uint64_t k0) {
          const auto [qb, qe] = dir.run(k0, k0 + len);
          if (!append_short(cand, n_cand, qb, qe)) range(qb, qe);
        });
        test_cand(n_cand);
      } else {
        each_row([&](std::uint64_t k0) { runs(k0, k0 + len); });
      }
    } else {
      for (Coords c = lo;;) {
        Coords w = c;
        if constexpr (B == Boundary::periodic) {
          for (int a = 0; a + 1 < D; ++a)
            if (wrap[a]) w[a] = c[a] < 0 ? c[a] + lv.n[a] : (c[a] >= lv.n[a] ? c[a] - lv.n[a] : c[a]);
        }
        if (lv.ranked) {
          w[D - 1] = 0;
          row_runs(lv.key(w), lo[D - 1], hi[D - 1], lv.n[D - 1], runs);
        } else {
          const std::int64_t n = lv.n[D - 1];
          for (std::int64_t k = lo[D - 1]; k <= hi[D - 1]; ++k) {
            w[D - 1] = k < 0 ? k + n : (k >= n ? k - n : k);
            const auto [qb, qe] = cell_range(lv, w);
            range(qb, qe);
          }
        }
        int a = D - 2;
        for (; a >= 0; --a) {
          if (++c[a] <= hi[a]) break;
          c[a] = lo[a];
        }
        if (a < 0) break;
      }
    }
    flush();
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
template <class Count>
Counters HGrid<D, B>::empty_counters() const {
  const int L = levels();
  Counters out;
  out.levels = L;
  if constexpr (!std::is_same_v<Count, PairsOnly>) out.particles_per_level = particles_per_level();
  if constexpr (Count::enabled) {
    out.accesses_by_level.assign(L * L, 0);
    out.checks_by_level.assign(L * L, 0);
    out.occupied_by_level.assign(L, 0);
    out.searches_by_level.assign(L * L, 0);
    out.rows_by_level.assign(L * L, 0);
  }
  return out;
}

template <int D, Boundary B>
template <Search S, class Count, class F>
void HGrid<D, B>::cells_phase(int h, std::uint64_t u0, std::uint64_t u1, F& f, Counters& out) const {
  const int L = levels();
  // A cell's half-stencil candidates: short ranges (most, on a sparse level)
  // as one list of indices appended without a data-dependent branch, longer
  // ones as ranges.
  std::array<std::pair<std::uint32_t, std::uint32_t>, detail::kHalfStencil<D>> nb;
  std::array<std::uint32_t, kShortRange * (detail::kHalfStencil<D> + 1)> cand;
  const auto& lv = levels_[h];
  detail::KeyWalk<D> walk(lv);
  const StencilRows rows = stencil_rows(lv);
  for_each_cell(lv, u0, u1, [&](std::uint64_t b, std::uint64_t key) {
    const std::uint32_t beg = start_[b], end = start_[b + 1];
    if constexpr (Count::enabled) {
      ++out.occupied_cells;
      ++out.occupied_by_level[h];
    }
    // Same level (linked cell): the half stencil is shared by the cell's
    // particles, nb_particles of them: n_cand in short ranges, the rest in
    // n_nb long ones.
    int n_nb = 0;
    std::uint32_t n_cand = 0;
    std::uint64_t nb_particles = 0;
    const Coords& c = walk.to(key);
    bool interior = true;  // not on the first or last cell of any axis
    for (int a = 0; a < D; ++a) interior = interior && c[a] >= 1 && c[a] + 1 < lv.n[a];
    const std::uint64_t nb_cells = half_stencil(lv, rows, c, key, b, interior, [&](std::uint32_t qb, std::uint32_t qe) {
      nb_particles += qe - qb;
      if (!append_short(cand, n_cand, qb, qe)) nb[n_nb++] = {qb, qe};
    });
    if constexpr (Count::enabled) out.probes += lv.ranked ? 0 : nb_cells;
    const bool plain = rows.plain_dx && interior;
    // Uncounted, a cell of several particles gathers its own particles and
    // its half stencil's into one contiguous run (in the order the tests
    // below take them), so that each particle tests one run from just past
    // itself, four at a time: the same pairs in the same order, without a
    // loop, a masked remainder and a setup per range (on a dense linked
    // cell, 1.4x faster: docs/record/PERFORMANCE.md, round 47).
    if constexpr (!Count::enabled && detail::kOverlap4) {
      std::uint32_t m = (end - beg) + n_cand;
      for (int k = 0; k < n_nb; ++k) m += nb[k].second - nb[k].first;
      if (end - beg >= kGatherMinParticles && m <= kGatherMax) {
        gather_and_test<S, Count>(h, beg, end, cand.data(), n_cand, nb.data(), n_nb, plain, f, out);
        return;
      }
    }
    const auto tests = [&]<Boundary TB>(std::uint32_t p) {
      test_range<Count, TB>(p, p + 1, end, f, out);
      test_list<Count, TB>(p, cand.data(), n_cand, f, out);
      for (int m = 0; m < n_nb; ++m) test_range<Count, TB>(p, nb[m].first, nb[m].second, f, out);
    };
    for (std::uint32_t p = beg; p < end; ++p) {
      if (plain) tests.template operator()<Boundary::walls>(p);
      else tests.template operator()<B>(p);
      if constexpr (Count::enabled) {
        const std::uint64_t acc = 1 + nb_cells;
        const std::uint64_t chk = (end - p - 1) + nb_particles;
        out.cell_accesses += acc;
        out.narrow_phase_checks += chk;
        out.list_checks += n_cand;
        out.runs += static_cast<std::uint64_t>(n_nb) + (end - p > 1);
        out.accesses_by_level[h * L + h] += acc;
        out.checks_by_level[h * L + h] += chk;
      }
      // Cross-level search (Eqs. 4-5), Bottom-Up: the levels above. Top-Down
      // searches the levels below in a second phase, in another order.
      if constexpr (S == Search::bottom_up) {
        for (int j = h + 1; j < L; ++j) cross_level<Count>(p, h, j, f, out);
      }
    }
  });
}

template <int D, Boundary B>
template <Search S, class Count, class F>
void HGrid<D, B>::gather_and_test(int h, std::uint32_t beg, std::uint32_t end, const std::uint32_t* cand,
                                  std::uint32_t n_cand, const std::pair<std::uint32_t, std::uint32_t>* nb, int n_nb,
                                  bool plain, F& f, Counters& out) const {
  // The run: the cell's particles, then the short ranges' candidates, then
  // the long ranges, with their sorted positions; padded to a multiple of
  // four with copies of the last (their lanes are masked off).
  alignas(32) std::array<std::array<double, kGatherMax + 4>, D + 1> gs;  // by coordinate, then radius
  std::array<std::uint32_t, kGatherMax + 4> gi;
  std::uint32_t m = 0;
  const auto put = [&](std::uint32_t q) {
    const Sphere<D>& sq = sorted_[q];
    for (int k = 0; k < D; ++k) gs[k][m] = sq.x[k];
    gs[D][m] = sq.r;
    gi[m++] = q;
  };
  for (std::uint32_t q = beg; q < end; ++q) put(q);
  for (std::uint32_t k = 0; k < n_cand; ++k) put(cand[k]);
  for (int k = 0; k < n_nb; ++k)
    for (std::uint32_t q = nb[k].first; q < nb[k].second; ++q) put(q);
  for (std::uint32_t t = m; t < m + 3; ++t) {
    for (int k = 0; k <= D; ++k) gs[k][t] = gs[k][m - 1];
    gi[t] = gi[m - 1];
  }
  // As test_range: dense or sparse appends (Emit::dense), the same pairs.
  const auto run = [&]<Boundary TB, bool Dense>(std::uint32_t p) {
    Sphere<D> sp;
    for (int k = 0; k < D; ++k) sp.x[k] = gs[k][p - beg];
    sp.r = gs[D][p - beg];
    std::uint32_t n = f.n, hits = 0;  // in registers over the run
    const std::uint32_t t0 = p - beg + 1;
    for (std::uint32_t t = t0; t < m; t += 4) {
      unsigned bits = detail::overlap4_soa<D, TB>(sp, gs, t, box_);
      if (t + 4 > m) bits &= (1u << (m - t)) - 1;
      if (!Dense && bits == 0) continue;
      if (n + 4 >= f.buf.size()) {  // room for four, and never full on return
        f.n = n;
        f.flush();
        n = 0;
      }
      n += detail::append4_indexed(f.buf.data() + n, p, gi.data() + t, bits);
      hits += Dense ? bits != 0 : 1;
    }
    f.n = n;
    f.tested((m - std::min(m, t0) + 3) / 4, hits);
  };
  const int L = levels();
  for (std::uint32_t p = beg; p < end; ++p) {
    if (plain) {
      if (f.dense()) run.template operator()<Boundary::walls, true>(p);
      else run.template operator()<Boundary::walls, false>(p);
    } else {
      if (f.dense()) run.template operator()<B, true>(p);
      else run.template operator()<B, false>(p);
    }
    if constexpr (S == Search::bottom_up) {
      for (int j = h + 1; j < L; ++j) cross_level<Count>(p, h, j, f, out);
    }
  }
}

template <int D, Boundary B>
auto HGrid<D, B>::plan(int threads, Search s) const -> std::vector<Task> {
  // Pieces of about `grain` particles, 32 per thread, handed out one at a
  // time (dynamic schedule): a piece's cost varies with its level and the
  // density of its region. The costliest pieces per particle go first, so
  // that the last ones handed out are small and alike: the Top-Down sweep
  // (large particles searching every level below), then the levels from the
  // top down.
  const std::uint64_t T = static_cast<std::uint64_t>(threads);
  const std::uint64_t grain = std::max<std::uint64_t>(64, size() / (32 * T));
  std::vector<Task> tasks;
  if (s == Search::top_down) {
    const std::uint64_t n = sweep_.size(), g = std::max<std::uint64_t>(4, n / (32 * T));
    for (std::uint64_t i = 0; i < n; i += g) tasks.push_back({-1, i, std::min(n, i + g)});
  }
  for (int h = levels() - 1; h >= 0; --h) {
    const auto& lv = levels_[h];
    const std::uint64_t n_h = level_begin_[h + 1] - level_begin_[h];
    if (n_h == 0) continue;
    const std::uint64_t units = lv.ranked ? lv.words : lv.slots;
    const std::uint64_t pieces = std::min<std::uint64_t>(units, (n_h + grain - 1) / grain);
    std::uint64_t u0 = 0;
    for (std::uint64_t k = 1; k <= pieces; ++k) {
      std::uint64_t u1 = units;
      if (k < pieces && lv.ranked) {  // the first word whose cells start at or after the k-th share of particles
        const std::uint64_t target = level_begin_[h] + n_h * k / pieces;
        std::uint64_t lo = u0, hi = units;
        while (lo < hi) {
          const std::uint64_t mid = lo + (hi - lo) / 2;
          if (start_[lv.bucket_base + rank_[lv.word_base + mid]] < target) lo = mid + 1;
          else hi = mid;
        }
        u1 = lo;
      } else if (k < pieces) {  // hashed: the keys are spread evenly over the slots
        u1 = units * k / pieces;
      }
      if (u1 > u0) tasks.push_back({h, u0, u1});
      u0 = u1;
    }
  }
  return tasks;
}

template <int D, Boundary B>
template <Search S, class Count, class F>
Counters HGrid<D, B>::query(F&& f_user, int threads) const {
  using FU = std::remove_reference_t<F>;
#if defined(_OPENMP)
  if (const int T = resolve_threads(threads); T > 1 && size() > 0) {
    const std::vector<Task> tasks = plan(T, S);
    std::vector<Counters> part(static_cast<std::size_t>(T));
    std::exception_ptr error;
    std::atomic<bool> failed{false};
    // Each thread: its own counters and pair buffer; the pieces handed out one
    // at a time. The counts are sums of integers, the same whatever the split.
#pragma omp parallel num_threads(T)
    {
      const int t = omp_get_thread_num();
      Counters local = empty_counters<Count>();
      auto work = [&](auto& g) {
        Emit<std::remove_reference_t<decltype(g)>> e{g, id_.data(), {}, 0};
#pragma omp for schedule(dynamic, 1) nowait
        for (std::size_t k = 0; k < tasks.size(); ++k) {
          if (failed.load(std::memory_order_relaxed)) continue;
          try {
            const Task& w = tasks[k];
            if (w.h >= 0) cells_phase<S, Count>(w.h, w.u0, w.u1, e, local);
            else top_down_sweep<Count>(w.u0, w.u1, e, local);
          } catch (...) {
#pragma omp critical(hgrid_query_error)
            if (!error) error = std::current_exception();
            failed = true;
          }
        }
        try {
          if (!failed.load()) e.flush();
        } catch (...) {
#pragma omp critical(hgrid_query_error)
          if (!error) error = std::current_exception();
          failed = true;
        }
      };
      if constexpr (kTakesThreadIndex<FU>) {
        WithThread<FU> g{f_user, t};
        work(g);
      } else {
        work(f_user);
      }
      part[static_cast<std::size_t>(t)] = std::move(local);
    }
    if (error) std::rethrow_exception(error);
    Counters out = empty_counters<Count>();
    for (const Counters& c : part)
      if (c.levels == out.levels) out.add(c);
    return out;
  }
#else
  (void)threads;  // one thread without OpenMP
#endif
  if constexpr (kTakesThreadIndex<FU>) {
    WithThread<FU> g{f_user, 0};
    return serial_query<S, Count>(g);
  } else {
    return serial_query<S, Count>(f_user);
  }
}

template <int D, Boundary B>
template <Search S>
auto HGrid<D, B>::counted_pieces(int threads) const -> std::vector<Piece> {
  std::vector<Piece> out;
  auto none = [](std::uint32_t, std::uint32_t) {};
  for (const Task& w : plan(std::max(1, threads), S)) {
    Piece piece{empty_counters<Counted>(), 0, w.h};
    Emit<decltype(none)> e{none, id_.data(), {}, 0};
    if (w.h >= 0) {
      cells_phase<S, Counted>(w.h, w.u0, w.u1, e, piece.counts);
      for_each_cell(levels_[w.h], w.u0, w.u1,
                    [&](std::uint64_t b, std::uint64_t) { piece.particles += start_[b + 1] - start_[b]; });
    } else {
      top_down_sweep<Counted>(w.u0, w.u1, e, piece.counts);
    }
    for (auto* v : {&piece.counts.accesses_by_level, &piece.counts.checks_by_level, &piece.counts.occupied_by_level,
                    &piece.counts.searches_by_level, &piece.counts.rows_by_level})
      *v = {};
    out.push_back(std::move(piece));
  }
  return out;
}

template <int D, Boundary B>
template <class Count, class F>
Counters HGrid<D, B>::for_each_overlap_below(std::span<const Sphere<D>> probes, F&& f) const {
  if (probes.size() >= (std::size_t{1} << 32)) throw InputError("probes", "at most 2^32 - 1 at a time");
  Counters out = empty_counters<Count>();
  if (size() == 0) return out;
  // The pairs go through a buffer as in a query, as (probe, sorted particle).
  Emit<std::remove_reference_t<F>, true> e{f, id_.data(), {}, 0};
  // The probes in the order of their cells on the top level, so that
  // consecutive searches meet the same directory words and particles in
  // the cache (in their given order, ~2x slower for the ghosts of a brick).
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(probes.size());
  const auto& top = levels_.back();
  auto wrapped = [&](std::size_t k) {
    Sphere<D> sp = probes[k];
    if constexpr (B == Boundary::periodic)  // the search box's wrap assumes a centre in the box
      for (int a = 0; a < D; ++a) sp.x[a] = detail::wrap(sp.x[a], box_[a]);
    return sp;
  };
  for (std::size_t k = 0; k < probes.size(); ++k) {
    const Sphere<D> sp = wrapped(k);
    Coords c;
    for (int a = 0; a < D; ++a) c[a] = top.cell_1d(sp.x[a], a);
    order[k] = {top.key(c), static_cast<std::uint32_t>(k)};
  }
  std::sort(order.begin(), order.end());
  for (const auto& [key, k] : order) {
    const Sphere<D> sp = wrapped(k);
    const int h = insertion_level(sp.r);
    for (int j = 0; j <= h; ++j) search_level<Count>(sp, k, h, j, e, out);
  }
  e.flush();
  return out;
}

template <int D, Boundary B>
template <Search S, class Count, class G>
Counters HGrid<D, B>::serial_query(G& g) const {
  Emit<G> e{g, id_.data(), {}, 0};
  Counters out = empty_counters<Count>();
  for (int h = 0; h < levels(); ++h) {
    const auto& lv = levels_[h];
    cells_phase<S, Count>(h, 0, lv.ranked ? lv.words : lv.slots, e, out);
  }
  if constexpr (S == Search::top_down) top_down_sweep<Count>(0, sweep_.size(), e, out);
  e.flush();
  return out;
}

template <int D, Boundary B>
template <class Count, class F>
void HGrid<D, B>::top_down_sweep(std::size_t i0, std::size_t i1, F& f, Counters& out) const {
  for (std::size_t i = i0; i < i1; ++i) {
    const std::uint32_t p = sweep_[i];
    // The level of p: the last level starting at or before it.
    const int h = static_cast<int>(std::upper_bound(level_begin_.begin(), level_begin_.end(), p) - level_begin_.begin()) - 1;
    for (int j = 0; j < h; ++j) cross_level<Count>(p, h, j, f, out);
  }
}

}  // namespace hgrid
