// The hierarchical grid (HGrid) of Krijgsman, Ogarko & Luding (2014), Sect. 2:
// a value type built from a span of spheres, a box and one params struct.
#pragma once
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <exception>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "hgridlab/grid/build_work.hpp"
#include "hgridlab/grid/counters.hpp"
#include "hgridlab/grid/detail/levels.hpp"
#include "hgridlab/grid/detail/overlap4.hpp"
#include "hgridlab/grid/detail/stencil.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/grid/params.hpp"
#include "hgridlab/base/threads.hpp"
#include "hgridlab/grid/uninit_vector.hpp"

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

  /// Rebuilds the grid for new particles (positions, radii, count) in the
  /// same box with the same params: the same grid as constructing a new one,
  /// but the arrays of the previous build are reused, and a workspace (22-40
  /// bytes per particle, workspace_bytes()) is kept for the next call: it
  /// allocates only when an array must grow beyond its largest size so far
  /// (more particles, a fuller cell range than before). If the input is
  /// rejected (InputError), the grid is left as it was.
  void rebuild(std::span<const Sphere<D>> spheres);
  /// Same, in a new box (a box that a simulation compresses, shears or
  /// grows): the levels are laid out again for it (periodic cells fitted to
  /// the new sides), in arrays kept from earlier calls, so that a box of the
  /// same number of levels allocates nothing. If the box or the input is
  /// rejected (InputError), the grid is left as it was, box included.
  void rebuild(std::span<const Sphere<D>> spheres, const Extent<D>& box);

  /// Hands every overlapping pair (distance < r_i + r_j; minimum image in a
  /// periodic box) to f(i, j) exactly once, with i < j the input indices,
  /// on `threads` threads (base/threads.hpp: 0 = all; the callback contract
  /// for more than one is stated there). Search direction and counting are
  /// compile-time policies. The pairs and the counters are the same for any
  /// number of threads; only the order of the calls differs. A const grid
  /// may be queried from several threads at once. A callback object with
  /// a member pairs(span) (or pairs(t, span)) gets the pairs in batches
  /// instead (base/threads.hpp, kTakesBatches).
  template <Search S, class Count = Uncounted, class F>
  Counters query(F&& f, int threads) const;
  /// Same, on the params struct's threads.
  template <Search S, class Count = Uncounted, class F>
  Counters query(F&& f) const {
    return query<S, Count>(std::forward<F>(f), params_.threads);
  }

  /// Calls f(k, j) for every particle j of the grid (input index) that
  /// overlaps probes[k] and lies on a level no higher than the probe's own
  /// level of insertion (Eq. 3; the top level for a probe larger than every
  /// cell): every j with r_j <= r_k among them. The probes need not be in
  /// the grid. One thread; the counters are those of the searches, counted
  /// as a Top-Down cross-level search counts its own (a probe's own level
  /// as its diagonal). A decomposed search finds the pairs of its ghosts
  /// this way (domain/decomposed_query.hpp).
  template <class Count = Uncounted, class F>
  Counters for_each_overlap_below(std::span<const Sphere<D>> probes, F&& f) const;

  /// Same as query, with the direction and threads of the params struct.
  template <class Count = Uncounted, class F>
  Counters for_each_pair(F&& f) const {
    return params_.search == Search::top_down ? query<Search::top_down, Count>(f)
                                              : query<Search::bottom_up, Count>(f);
  }

  /// One piece of a query's work on several threads: the pieces are handed
  /// out one at a time, in order (base/threads.hpp). Its counts (scalars
  /// only: the by-level matrices are left empty), the particles whose
  /// same-level cells it covers, and its level (-1: a part of the Top-Down
  /// cross-level sweep).
  struct Piece {
    Counters counts;
    std::uint64_t particles = 0;
    int level = 0;
  };
  /// The counted work of every piece of a query on `threads` threads (run
  /// here one piece after the other): what a simulation of the load balance
  /// of more threads than a machine has needs (measure/balance.hpp).
  template <Search S>
  std::vector<Piece> counted_pieces(int threads) const;

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
  /// Size of the cell directory the build fills: bitmap words of the ranked
  /// levels (one per 64 cells, plus one) and table slots of the hashed ones.
  std::uint64_t directory_words() const { return words_.size(); }
  std::uint64_t directory_slots() const { return keys_.size(); }
  /// The sort's passes (grid/build_work.hpp) of the last build.
  SortWork sort_work() const {
    SortWork w;
    for (std::size_t h = 0; h < levels_.size(); ++h) {
      const LevelSortWork l = level_sort_work(levels_[h].cells(), size(), levels());
      w.particle_passes += double(l.passes) * double(level_begin_[h + 1] - level_begin_[h]);
      w.bucket_passes += double(l.passes) * double(l.buckets);
    }
    return w;
  }
  const GridParams& params() const { return params_; }
  const Extent<D>& box() const { return box_; }

  /// Where a sphere is (or would be) stored: its level of insertion (0-based,
  /// the lowest h with 2 r <= s_h) and the linear index of its cell in that
  /// level (last axis fastest; a periodic centre is wrapped into the box first).
  struct Placement {
    int level;
    std::uint64_t cell;
  };
  Placement placement(const Sphere<D>& s) const {
    const int h = insertion_level(s.r);
    std::array<double, D> x = s.x;
    if constexpr (B == Boundary::periodic)
      for (int a = 0; a < D; ++a) x[a] = detail::wrap(x[a], box_[a]);
    return {h, levels_[h].key(levels_[h].cell(x))};
  }
  /// Bytes of the workspace kept by rebuild() (none after construction).
  std::size_t workspace_bytes() const { return scratch_.bytes(); }
  /// Bytes held by the grid, including its sorted copy of the particles
  /// (not counting the workspace of rebuild()).
  std::size_t memory_bytes() const {
    return sorted_.capacity() * sizeof(Sphere<D>) + id_.capacity() * sizeof(std::uint32_t) +
           start_.capacity() * sizeof(std::uint32_t) + keys_.capacity() * sizeof(std::uint64_t) +
           slot_bucket_.capacity() * sizeof(std::uint32_t) +
           words_.capacity() * sizeof(std::uint64_t) + rank_.capacity() * sizeof(std::uint32_t) +
           sweep_.capacity() * sizeof(std::uint32_t) + levels_.capacity() * sizeof(detail::Level<D>);
  }

 private:
  /// The level of insertion: the lowest h with 2 r <= s_h (Eq. 3); the
  /// effective sizes never decrease with h.
  int insertion_level(double r) const {
    int h = 0;
    while (h < levels() - 1 && 2 * r > levels_[h].s_min) ++h;
    return h;
  }
  using Coords = std::array<std::int64_t, D>;

  /// Working arrays of a build (keys, coarse buckets, in-bucket sort
  /// buffers, sweep-order keys): freed after construction, kept by rebuild().
  /// Not part of the grid's value: a copy of a grid starts without one.
  struct Scratch {
    Scratch() = default;
    Scratch(const Scratch&) {}
    Scratch(Scratch&&) = default;
    Scratch& operator=(const Scratch&) { return *this; }
    Scratch& operator=(Scratch&&) = default;
    detail::UninitVector<std::uint64_t> key_in, key, tkey, k0, tk;
    detail::UninitVector<std::uint32_t> coarse, order, torder, tid, t;
    detail::UninitVector<Sphere<D>> tsph;
    std::vector<std::uint32_t> cursor, bucket_begin, coarse_base, cells_before, sorting;
    std::vector<int> shift, level_of;
    std::vector<double> d_max_of;               // per thread
    std::vector<std::exception_ptr> error_of;   // per thread
    std::vector<detail::Level<D>> levels;       // rebuild(spheres, box): the new box's levels, swapped in
    std::size_t bytes() const {
      return (key_in.capacity() + key.capacity() + tkey.capacity() + k0.capacity() + tk.capacity()) *
                 sizeof(std::uint64_t) +
             (coarse.capacity() + order.capacity() + torder.capacity() + tid.capacity() + t.capacity() +
              cursor.capacity() + bucket_begin.capacity() + coarse_base.capacity() + cells_before.capacity() +
              sorting.capacity()) *
                 sizeof(std::uint32_t) +
             d_max_of.capacity() * sizeof(double) + error_of.capacity() * sizeof(std::exception_ptr) +
             level_of.capacity() * sizeof(int) +
             tsph.capacity() * sizeof(Sphere<D>) + shift.capacity() * sizeof(int) +
             levels.capacity() * sizeof(detail::Level<D>);
    }
  };
  /// A build runs on at most one thread per this many particles.
  static constexpr std::size_t kMinParticlesPerThread = 1024;
  /// Sorts the particles into the levels' cells and fills the directory
  /// (levels_ must hold the geometry of params_ and box_).
  void build(std::span<const Sphere<D>> spheres, Scratch& ws);

  /// Bucket of the cell with this key, or kNoBucket if the cell is empty.
  std::uint64_t bucket(const detail::Level<D>& L, std::uint64_t key) const {
    if (L.ranked) {
      const std::uint64_t w = L.word_base + (key >> 6);
      const std::uint64_t bit = std::uint64_t{1} << (key & 63);
      const std::uint64_t word = words_[w];
      if (!(word & bit)) return detail::kNoBucket;
      return L.bucket_base + rank_[w] + static_cast<std::uint64_t>(std::popcount(word & (bit - 1)));
    }
    const std::uint64_t mask = L.slots - 1;
    std::uint64_t slot = detail::hash_key(key) >> L.shift;
    for (;;) {
      const std::uint64_t k = keys_[L.key_base + slot];
      if (k == key) return L.bucket_base + slot_bucket_[L.key_base + slot];
      if (k == detail::kEmptyKey) return detail::kNoBucket;
      slot = (slot + 1) & mask;
    }
  }
  /// A ranked level's directory as plain pointers, buckets counted from the
  /// level's first (so that the loops using it keep them in registers).
  struct RankView {
    const std::uint64_t* words;
    const std::uint32_t* ranks;
    const std::uint32_t* start;  // start_ from the level's first bucket
    /// The first bucket at or after cell key k (0 <= k <= cells).
    [[gnu::always_inline]] std::uint32_t rank(std::uint64_t k) const {
      const std::uint64_t below = (std::uint64_t{1} << (k & 63)) - 1;
      return ranks[k >> 6] + static_cast<std::uint32_t>(std::popcount(words[k >> 6] & below));
    }
    /// The particles of the cells with keys in [k0, k1), which are one
    /// contiguous range of the sorted array because buckets follow keys.
    [[gnu::always_inline]] std::pair<std::uint32_t, std::uint32_t> run(std::uint64_t k0, std::uint64_t k1) const {
      return {start[rank(k0)], start[rank(k1)]};
    }
  };
  RankView rank_view(const detail::Level<D>& L) const {
    return {words_.data() + L.word_base, rank_.data() + L.word_base, start_.data() + L.bucket_base};
  }
  /// Calls f(bucket, cell key) for every non-empty cell of level L.
  template <class F>
  void for_each_cell(const detail::Level<D>& L, F&& f) const {
    for_each_cell(L, 0, L.ranked ? L.words : L.slots, f);
  }
  /// Same, for the cells of bitmap words [u0, u1) of a ranked level, or of
  /// table slots [u0, u1) of a hashed one.
  template <class F>
  void for_each_cell(const detail::Level<D>& L, std::uint64_t u0, std::uint64_t u1, F&& f) const {
    if (L.ranked) {
      std::uint64_t b = L.bucket_base + (u0 < L.words ? rank_[L.word_base + u0] : L.buckets);
      for (std::uint64_t w = u0; w < u1; ++w)
        for (std::uint64_t bits = words_[L.word_base + w]; bits; bits &= bits - 1)
          f(b++, (w << 6) | static_cast<std::uint64_t>(std::countr_zero(bits)));
      return;
    }
    for (std::uint64_t k = u0; k < u1; ++k)
      if (keys_[L.key_base + k] != detail::kEmptyKey)
        f(L.bucket_base + slot_bucket_[L.key_base + k], keys_[L.key_base + k]);
  }
  /// Content of the cell with the given coordinates at level L: [begin, end).
  std::pair<std::uint32_t, std::uint32_t> cell_range(const detail::Level<D>& L, const Coords& c) const {
    const std::uint64_t b = bucket(L, L.key(c));
    if (b == detail::kNoBucket) return {0, 0};
    return {start_[b], start_[b + 1]};
  }
  /// Splits the cells [lo, hi] of the row starting at key `row` (along axis
  /// D-1, n cells, hi - lo < n) into at most two runs of keys at a periodic
  /// seam, and calls g(k0, k1) for each.
  template <class G>
  static void row_runs(std::uint64_t row, std::int64_t lo, std::int64_t hi, std::int64_t n, G& g) {
    const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
    if (lo < 0) {
      g(row + u(n + lo), row + u(n));
      g(row, row + u(hi + 1));
    } else if (hi >= n) {
      g(row + u(lo), row + u(n));
      g(row, row + u(hi - n + 1));
    } else {
      g(row + u(lo), row + u(hi + 1));
    }
  }
  /// Key offsets, from a cell to the rows of its half stencil (the offsets
  /// of the axes before the row axis D-1 whose first non-zero component is
  /// +1), valid on a ranked level with at least 3 cells per periodic axis.
  struct StencilRows {
    std::array<std::int64_t, detail::kHalfStencil<D - 1>> delta{};
    RankView dir{};  // valid on a ranked level
    bool valid = false;
    /// Periodic level with at least 5 cells per axis: between an interior
    /// cell and its neighbours |dx| < 2 s + rounding < A / 2 on every axis,
    /// so the minimum image is the plain difference.
    bool plain_dx = false;
  };
  StencilRows stencil_rows(const detail::Level<D>& L) const;
  /// Number of cells of the same-level half stencil of the non-empty cell
  /// with coordinates c, key and bucket b (docs/MODEL.md section 1; interior: c is
  /// on neither the first nor the last cell of any axis); calls
  /// add(begin, end) with the particles of its cells, a row of cells at a
  /// time where the level allows it (a range may be empty).
  template <class Add>
  std::uint64_t half_stencil(const detail::Level<D>& L, const StencilRows& rows, const Coords& c,
                             std::uint64_t key, std::uint64_t b, bool interior, Add&& add) const;

  /// Candidate ranges of at most this many particles are appended to an
  /// index list without a branch on their length (see append_short).
  static constexpr std::uint32_t kShortRange = 4;
  /// Appends the range [qb, qe) to cand at n if it is short (returns true),
  /// with a fixed kShortRange-wide store: cand needs kShortRange free entries
  /// past n whatever the range's length.
  template <std::size_t C>
  static bool append_short(std::array<std::uint32_t, C>& cand, std::uint32_t& n, std::uint32_t qb, std::uint32_t qe) {
    if (qe - qb > kShortRange) return false;
    std::uint32_t* const d = cand.data() + n;  // not cand[n + t]: 32-bit index arithmetic does not combine into one store
    for (std::uint32_t t = 0; t < kShortRange; ++t) d[t] = qb + t;
    n += qe - qb;
    return true;
  }

  /// Buffers the overlapping pairs (as sorted positions) and hands them to
  /// the callback, as input indices i < j, a batch at a time, so that an
  /// overlap test can do without a branch on its outcome.
  /// Probe = true: the first of a pair is a probe's number, handed out as
  /// it is (for_each_overlap_below), f(probe, input index).
  template <class F, bool Probe = false>
  struct Emit {
    F& f;
    const std::uint32_t* id;
    std::array<std::pair<std::uint32_t, std::uint32_t>, 64> buf;
    std::uint32_t n = 0;
    /// The runs' groups of four tested lately, and how many of them held a
    /// pair: where at least one in kDenseHits does, a run appends each
    /// group's pairs without a branch on the outcome (a branch taken that
    /// often mispredicts); else it skips the groups without a pair (most,
    /// and the branch predicts well). Either way the same pairs in the same
    /// order; halved now and then, so they follow the query's regions.
    std::uint32_t groups = 0, hit_groups = 0;
    static constexpr std::uint32_t kDenseHits = 8;
    bool dense() const { return hit_groups * kDenseHits > groups; }
    void tested(std::uint32_t g, std::uint32_t h) {
      groups += g;
      hit_groups += h;
      if (groups > (1u << 14)) {
        groups >>= 1;
        hit_groups >>= 1;
      }
    }
    void flush() {
      if constexpr (!Probe && kTakesBatches<F>) {  // base/threads.hpp
        for (std::uint32_t k = 0; k < n; ++k) {
          const std::uint32_t i = id[buf[k].first], j = id[buf[k].second];
          const std::uint32_t lo = std::min(i, j);
          buf[k] = {lo, i ^ j ^ lo};  // no branch: the order of i and j is random
        }
        f.pairs(std::span<const IndexPair>(buf.data(), n));
        n = 0;
        return;
      }
      for (std::uint32_t k = 0; k < n; ++k) {
        if constexpr (Probe) {
          f(buf[k].first, id[buf[k].second]);
        } else {
          const std::uint32_t i = id[buf[k].first], j = id[buf[k].second];
          f(std::min(i, j), std::max(i, j));  // no branch: the order of i and j is random
        }
      }
      n = 0;
    }
  };

  /// Overlap test of sorted particles p and q; an overlapping pair goes to
  /// the buffer. Branchy: for long runs of candidates, which rarely overlap
  /// (a linked cell's cells), where the branch predicts well.
  /// TB = walls skips the minimum image where it cannot change the
  /// displacement (same result, bit for bit).
  template <class Count, Boundary TB = B, class E>
  void test(std::uint32_t p, std::uint32_t q, E& e, Counters& out) const {
    test<Count, TB>(sorted_[p], p, q, e, out);
  }
  /// Same, for sphere sp, handed out as p (a probe's number, or sorted_[p]).
  template <class Count, Boundary TB = B, class E>
  void test(const Sphere<D>& sp, std::uint32_t p, std::uint32_t q, E& e, Counters& out) const {
    if constexpr (!Count::tests) return;
    if (detail::overlap<D, TB>(sp, sorted_[q], box_)) {
      if constexpr (Count::enabled) ++out.contacts;
      e.buf[e.n++] = {p, q};
      if (e.n == e.buf.size()) e.flush();
    }
  }
  /// Appends to e's buffer the pairs (p, q + t) of the set bits t of one
  /// group of four (detail::append4); n: the buffer's fill, held by the
  /// caller. Dense: no branch on the outcome (Emit::dense).
  template <bool Dense, class E>
  static void add_group(E& e, std::uint32_t& n, std::uint32_t& hit_groups, std::uint32_t p, std::uint32_t q,
                        unsigned bits) {
    if (!Dense && bits == 0) return;
    if (n + 4 >= e.buf.size()) {  // room for four, and never full on return
      e.n = n;
      e.flush();
      n = 0;
    }
    n += detail::append4(e.buf.data() + n, p, q, bits);
    hit_groups += Dense ? bits != 0 : 1;
  }
  /// Overlap tests of sp (handed out as p) against the run [qb, qe) of
  /// sorted particles, four at a time (detail/overlap4.hpp: each lane the
  /// scalar test's arithmetic), the last one to three as four whose lanes
  /// beyond the run are masked off (one at a time only at the array's end);
  /// each four's pairs appended to the buffer (add_group). The same pairs in
  /// the same order as test() over the run. For long runs (a dense cell).
  template <class Count, Boundary TB = B, class E>
  void test_range(const Sphere<D>& sp, std::uint32_t p, std::uint32_t qb, std::uint32_t qe, E& e,
                  Counters& out) const {
    if constexpr (!Count::tests) return;
    std::uint32_t q = qb;
    if constexpr (detail::kOverlap4) {
      const Sphere<D>* const s = sorted_.data();
      const auto run = [&]<bool Dense>() {
        std::uint32_t n = e.n, hits = 0;  // in registers over the run
        const std::uint32_t q0 = q;
        for (; q + 4 <= qe; q += 4) {
          const unsigned bits = detail::overlap4<D, TB>(sp, s + q, box_);
          if constexpr (Count::enabled) out.contacts += static_cast<std::uint64_t>(std::popcount(bits));
          add_group<Dense>(e, n, hits, p, q, bits);
        }
        if (q < qe && q + 4 <= sorted_.size()) {
          const unsigned bits = detail::overlap4<D, TB>(sp, s + q, box_) & ((1u << (qe - q)) - 1);
          if constexpr (Count::enabled) out.contacts += static_cast<std::uint64_t>(std::popcount(bits));
          add_group<Dense>(e, n, hits, p, q, bits);
          q = qe;
        }
        e.n = n;
        e.tested((q - q0 + 3) / 4, hits);
      };
      if (e.dense()) run.template operator()<true>();
      else run.template operator()<false>();
    }
    for (; q < qe; ++q) test<Count, TB>(sp, p, q, e, out);
  }
  /// Same, for sorted particle p.
  template <class Count, Boundary TB = B, class E>
  void test_range(std::uint32_t p, std::uint32_t qb, std::uint32_t qe, E& e, Counters& out) const {
    test_range<Count, TB>(sorted_[p], p, qb, qe, e, out);
  }

  /// Overlap tests of p against a list of candidates, without a branch on
  /// their outcome: for the short candidate lists of sparse levels, where
  /// about one check in six overlaps. The buffer's fill count and p's sphere
  /// stay in registers.
  template <class Count, Boundary TB = B, class E>
  void test_list(std::uint32_t p, const std::uint32_t* cand, std::uint32_t n_cand, E& e, Counters& out) const {
    test_list<Count, TB>(sorted_[p], p, cand, n_cand, e, out);
  }
  /// Same, for sphere sp, handed out as p.
  template <class Count, Boundary TB = B, class E>
  void test_list(const Sphere<D> sp, std::uint32_t p, const std::uint32_t* cand, std::uint32_t n_cand, E& e,
                 Counters& out) const {
    if constexpr (!Count::tests) return;
    const Sphere<D>* const s = sorted_.data();
    std::uint32_t n = e.n;
    for (std::uint32_t m = 0; m < n_cand; ++m) {
      const std::uint32_t q = cand[m];
      const bool hit = detail::overlap<D, TB>(sp, s[q], box_);
      if constexpr (Count::enabled) out.contacts += hit;
      e.buf[n] = {p, q};
      n += hit;
      if (n == e.buf.size()) {
        e.n = n;
        e.flush();
        n = 0;
      }
    }
    e.n = n;
  }

  /// A thread's callback f(t, i, j) seen as g(i, j) (base/threads.hpp).
  template <class F>
  struct WithThread {
    F& f;
    int t;
    void operator()(std::uint32_t i, std::uint32_t j) { f(t, i, j); }
    void pairs(std::span<const IndexPair> s)
      requires kTakesBatchesWithThread<F>
    {
      f.pairs(t, s);
    }
  };

  template <class Count, class F>
  void cross_level(std::uint32_t p, int h, int j, F& f, Counters& out) const {
    search_level<Count>(sorted_[p], p, h, j, f, out);
  }
  /// The cross-level search of sphere sp (of level h, handed out as p) on
  /// level j: the cells of its search box (Eq. 4).
  template <class Count, class F>
  void search_level(const Sphere<D>& sp, std::uint32_t p, int h, int j, F& f, Counters& out) const;
  /// Same-level phase (and Bottom-Up's cross-level searches) of the cells of
  /// level h in words (ranked) or slots (hashed) [u0, u1).
  template <Search S, class Count, class F>
  void cells_phase(int h, std::uint64_t u0, std::uint64_t u1, F& f, Counters& out) const;
  /// Uncounted same-level tests (and Bottom-Up's cross-level searches) of
  /// the cell [beg, end) of level h, its half stencil's candidates gathered
  /// into one run (cells_phase). Cells of at least kGatherMinParticles
  /// particles and at most kGatherMax in all, a copy on the stack.
  template <Search S, class Count, class F>
  void gather_and_test(int h, std::uint32_t beg, std::uint32_t end, const std::uint32_t* cand, std::uint32_t n_cand,
                       const std::pair<std::uint32_t, std::uint32_t>* nb, int n_nb, bool plain, F& f,
                       Counters& out) const;
  static constexpr std::uint32_t kGatherMinParticles = 2, kGatherMax = 508;
  /// Top-Down cross-level phase: the particles sweep_[i0, i1) search the
  /// levels below their own, in the order of sweep_.
  template <class Count, class F>
  void top_down_sweep(std::size_t i0, std::size_t i1, F& f, Counters& out) const;
  /// A piece of a query's work: level h's cells in words or slots [u0, u1),
  /// or, with h = -1, sweep_[u0, u1).
  struct Task {
    int h;
    std::uint64_t u0, u1;
  };
  std::vector<Task> plan(int threads, Search s) const;
  template <class Count>
  Counters empty_counters() const;
  template <Search S, class Count, class G>
  Counters serial_query(G& g) const;

  GridParams params_;
  Extent<D> box_{};
  std::vector<detail::Level<D>> levels_;
  detail::UninitVector<Sphere<D>> sorted_;      // particles sorted by (level, cell)
  detail::UninitVector<std::uint32_t> id_;      // input index of each sorted particle
  detail::UninitVector<std::uint32_t> start_;   // bucket -> first sorted particle; one past the last bucket too
  std::vector<std::uint64_t> keys_;      // cell keys of the hashed levels' tables
  std::vector<std::uint32_t> slot_bucket_;  // bucket (within its level) of each table slot
  std::vector<std::uint64_t> words_;     // ranked levels: one bit per cell, set if non-empty
  std::vector<std::uint32_t> rank_;      // ranked levels: set bits before each word (within its level)
  std::vector<std::uint32_t> level_begin_;  // first sorted particle of each level, plus N
  std::vector<std::uint32_t> sweep_;     // the particles above the lowest level, by their lowest-level cell
  Scratch scratch_;                      // rebuild()'s workspace
};

}  // namespace hgrid

#include "hgridlab/grid/detail/hgrid_build.hpp"
#include "hgridlab/grid/detail/hgrid_query.hpp"
