// Sums over contact pairs in canonical order, (i, j) ascending, on several
// threads, with the same result bit for bit as one thread summing in that
// order (the DPM engine's forces and torques).
//
// A particle p receives, in canonical order, first the contributions of the
// pairs (i, p), i < p, in increasing i, then those of (p, j) in increasing j.
// With T threads the pairs are sorted into that order (a partition by first
// index into T ranges of particles balanced by the number of pair ends they
// hold, then a radix sort per range),
// every pair's contribution is computed once into an array (the costly part,
// split evenly by pair), and each thread then adds, for the particles of its
// range only, the contributions of earlier ranges' pairs (i, p) followed by
// its own pairs in key order: each particle sees the same additions, in the
// same order, as with one thread. On one thread nothing is stored: each
// pair's contribution is computed and added at once.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <span>
#include <type_traits>
#include <vector>

#include "hgridlab/base/parallel.hpp"
#include "hgridlab/base/radix.hpp"
#include "hgridlab/contacts/pair_keys.hpp"
#include "hgridlab/base/threads.hpp"

namespace hgrid {

class PairSum {
 public:
  /// For particle indices below n.
  explicit PairSum(std::size_t n) : pk_(n), n_(n) {}

  std::uint64_t key(std::uint32_t i, std::uint32_t j) const { return pk_.key(i, j); }
  std::uint32_t first(std::uint64_t key) const { return pk_.first(key); }
  std::uint32_t second(std::uint64_t key) const { return pk_.second(key); }

  /// Takes the pairs found by lists.size() threads (one key list each, from
  /// key(); the lists are left as they are) and puts them in canonical order.
  void gather(const std::vector<std::vector<std::uint64_t>>& lists);

  /// Takes pairs already in canonical order as compressed rows (the
  /// partners j > i of particle i ascending, `partners[start[i]]` to
  /// `partners[start[i + 1] - 1]`; a ContactList's contacts), to be summed
  /// on `threads` ranges of particles (0 = all) cut where the pairs before
  /// the cut reach each range's share. No sort.
  void assign_rows(std::span<const std::uint32_t> start, std::span<const std::uint32_t> partners, int threads);

  /// The pairs gathered, as compressed rows: the partners j > i of
  /// particle i are partners[start[i]] .. partners[start[i + 1] - 1],
  /// ascending (the arrays' capacity is reused).
  void rows(std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& partners) const {
    start.assign(n_ + 1, 0);
    partners.resize(keys_.size());
    for (std::size_t m = 0; m < keys_.size(); ++m) {
      ++start[pk_.first(keys_[m]) + 1];
      partners[m] = pk_.second(keys_[m]);
    }
    for (std::size_t i = 0; i < n_; ++i) start[i + 1] += start[i];
  }

  /// The pairs in canonical order, after gather().
  const std::vector<std::uint64_t>& keys() const { return keys_; }

  /// Calls, for every particle p of [0, n) in ascending order within each
  /// thread's range: begin(p); then for each of its pairs in canonical order,
  /// with R r = compute(i, j) (i < j), second(r, p) if p is j, first(r, p)
  /// if p is i; then end(p). compute must depend on the pair alone, and
  /// first, second, begin, end may change only particle p's state. `results`
  /// is scratch space (kept between calls). compute may also take the
  /// pair's place in keys() as a third argument, compute(i, j, k) (per-pair
  /// data such as a contact's history; each k is computed once). Exceptions from the callbacks
  /// reach the caller (the lowest thread's first).
  template <class R, class Compute, class Begin, class First, class Second, class End>
  void sum(std::vector<R>& results, Compute&& compute, Begin&& begin, First&& first, Second&& second, End&& end);

 private:
  template <class Compute>
  static decltype(auto) call(Compute& compute, std::uint32_t i, std::uint32_t j, std::size_t k) {
    if constexpr (std::is_invocable_v<Compute&, std::uint32_t, std::uint32_t, std::size_t>) return compute(i, j, k);
    else return compute(i, j);
  }

  detail::PairKeys pk_;
  std::size_t n_;
  std::vector<std::uint64_t> keys_, tmp_;
  std::vector<std::size_t> counts_;      // pairs per (list, coarse bucket of the first index), then write positions
  std::vector<std::size_t> ends_;        // pairs per (list, coarse bucket of the second index)
  std::vector<std::uint32_t> range_p_;   // ranges' first particles, T + 1 entries (last = n)
  std::vector<std::size_t> range_k_;     // ranges' first keys, T + 1 entries
  std::vector<std::vector<std::size_t>> cross_;  // per (chunk, range): pairs (i, p) of p in the range, i before it
};

inline void PairSum::gather(const std::vector<std::vector<std::uint64_t>>& lists) {
  const int T = static_cast<int>(std::max<std::size_t>(1, lists.size()));
  std::size_t total = 0;
  for (const auto& l : lists) total += l.size();
  keys_.resize(total);
  tmp_.resize(total);
  const int n_bits = pk_.bits(), key_bits = 2 * n_bits;
  if (T == 1 || total == 0) {
    auto out = keys_.begin();
    for (const auto& l : lists) out = std::copy(l.begin(), l.end(), out);
    detail::radix_sort_keys(keys_.data(), tmp_.data(), total, key_bits);
    range_p_ = {0, static_cast<std::uint32_t>(n_)};
    range_k_ = {0, total};
    return;
  }
  // Coarse buckets of the particle index, 64 per thread: the ranges hold
  // about equal numbers of pair ends (the sums' work), to within a bucket.
  const int cb = std::min(n_bits, static_cast<int>(std::bit_width(static_cast<unsigned>(64 * T))));
  const int shift = key_bits - cb;  // key >> shift: the first index's top cb bits
  const std::size_t nb = std::size_t{1} << cb;
  counts_.assign(static_cast<std::size_t>(T) * nb, 0);
  ends_.assign(static_cast<std::size_t>(T) * nb, 0);
  const int second_shift = n_bits - cb;
  range_p_.assign(static_cast<std::size_t>(T) + 1, 0);
  range_k_.assign(static_cast<std::size_t>(T) + 1, 0);
#if defined(_OPENMP)
#pragma omp parallel num_threads(T)
#endif
  {
    const auto [t, team] = detail::team_slot();
    // Thread t handles the lists t, t + team, ... (all of them if the team is smaller than asked).
    for (int l = t; l < T; l += team) {
      std::size_t* c = counts_.data() + static_cast<std::size_t>(l) * nb;
      std::size_t* e = ends_.data() + static_cast<std::size_t>(l) * nb;
      for (const std::uint64_t k : lists[static_cast<std::size_t>(l)]) {
        ++c[k >> shift];
        ++e[pk_.second(k) >> second_shift];
      }
    }
#if defined(_OPENMP)
#pragma omp barrier
#pragma omp single
#endif
    {
      // Write positions, bucket-major; ranges cut at bucket edges.
      std::size_t at = 0, ends = 0;
      int r = 1;
      for (std::size_t b = 0; b < nb; ++b) {
        while (r < T && ends >= 2 * total * static_cast<std::size_t>(r) / static_cast<std::size_t>(T)) {
          range_p_[static_cast<std::size_t>(r)] = static_cast<std::uint32_t>(std::min(n_, b << (n_bits - cb)));
          range_k_[static_cast<std::size_t>(r)] = at;
          ++r;
        }
        for (int l = 0; l < T; ++l) {
          ends += counts_[static_cast<std::size_t>(l) * nb + b] + ends_[static_cast<std::size_t>(l) * nb + b];
          std::size_t& c = counts_[static_cast<std::size_t>(l) * nb + b];
          const std::size_t k = c;
          c = at;
          at += k;
        }
      }
      for (; r < T; ++r) {
        range_p_[static_cast<std::size_t>(r)] = static_cast<std::uint32_t>(n_);
        range_k_[static_cast<std::size_t>(r)] = total;
      }
      range_p_[static_cast<std::size_t>(T)] = static_cast<std::uint32_t>(n_);
      range_k_[static_cast<std::size_t>(T)] = total;
    }  // implicit barrier
    for (int l = t; l < T; l += team) {
      std::size_t* c = counts_.data() + static_cast<std::size_t>(l) * nb;
      for (const std::uint64_t k : lists[static_cast<std::size_t>(l)]) keys_[c[k >> shift]++] = k;
    }
#if defined(_OPENMP)
#pragma omp barrier
#endif
    for (int r = t; r < T; r += team) {
      const std::size_t lo = range_k_[static_cast<std::size_t>(r)], hi = range_k_[static_cast<std::size_t>(r) + 1];
      detail::radix_sort_keys(keys_.data() + lo, tmp_.data() + lo, hi - lo, key_bits);
    }
  }
}

inline void PairSum::assign_rows(std::span<const std::uint32_t> start, std::span<const std::uint32_t> partners,
                                 int threads) {
  const std::size_t K = partners.size();
  keys_.resize(K);
  for (std::size_t i = 0; i + 1 < start.size(); ++i)
    for (std::uint32_t m = start[i]; m < start[i + 1]; ++m)
      keys_[m] = pk_.key(static_cast<std::uint32_t>(i), partners[m]);
  const int T = std::max(1, resolve_threads(threads));
  range_p_.assign(static_cast<std::size_t>(T) + 1, static_cast<std::uint32_t>(n_));
  range_k_.assign(static_cast<std::size_t>(T) + 1, K);
  range_p_[0] = 0;
  range_k_[0] = 0;
  for (int r = 1; r < T; ++r) {  // the first particle whose pairs start at or after the share
    const std::size_t share = K * static_cast<std::size_t>(r) / static_cast<std::size_t>(T);
    const auto p = static_cast<std::size_t>(std::lower_bound(start.begin(), start.end() - 1, share) - start.begin());
    range_p_[static_cast<std::size_t>(r)] = static_cast<std::uint32_t>(std::max<std::size_t>(p, range_p_[r - 1]));
    range_k_[static_cast<std::size_t>(r)] = start[range_p_[static_cast<std::size_t>(r)]];
  }
}

template <class R, class Compute, class Begin, class First, class Second, class End>
void PairSum::sum(std::vector<R>& results, Compute&& compute, Begin&& begin, First&& first, Second&& second,
                  End&& end) {
  const int T = static_cast<int>(range_p_.size()) - 1;
  if (T <= 1) {
    for (std::size_t p = 0; p < n_; ++p) begin(p);
    for (std::size_t k = 0; k < keys_.size(); ++k) {
      const std::uint32_t i = pk_.first(keys_[k]), j = pk_.second(keys_[k]);
      const R r = call(compute, i, j, k);
      first(r, i);
      second(r, j);
    }
    for (std::size_t p = 0; p < n_; ++p) end(p);
    return;
  }
  const std::size_t K = keys_.size();
  results.resize(K);
  cross_.resize(static_cast<std::size_t>(T) * static_cast<std::size_t>(T));
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(T));
  auto owner = [&](std::uint32_t p) {  // the range holding particle p
    return static_cast<int>(std::upper_bound(range_p_.begin() + 1, range_p_.end() - 1, p) - (range_p_.begin() + 1));
  };
#if defined(_OPENMP)
#pragma omp parallel num_threads(T)
#endif
  {
    const auto [t, team] = detail::team_slot();
    try {
      // Every pair's contribution, T even chunks of the pairs; chunk c notes
      // for each range the pairs whose second particle lies there but not
      // their first.
      for (int c = t; c < T; c += team) {
        const std::size_t lo = K * static_cast<std::size_t>(c) / static_cast<std::size_t>(T);
        const std::size_t hi = K * (static_cast<std::size_t>(c) + 1) / static_cast<std::size_t>(T);
        auto* notes = cross_.data() + static_cast<std::size_t>(c) * static_cast<std::size_t>(T);
        for (int r = 0; r < T; ++r) notes[r].clear();
        for (std::size_t k = lo; k < hi; ++k) {
          const std::uint32_t i = pk_.first(keys_[k]), j = pk_.second(keys_[k]);
          results[k] = call(compute, i, j, k);
          const int oj = owner(j);
          if (oj != owner(i)) notes[oj].push_back(k);
        }
      }
    } catch (...) {
      errors[static_cast<std::size_t>(t)] = std::current_exception();
    }
#if defined(_OPENMP)
#pragma omp barrier
#endif
    try {
      for (int r = t; r < T; r += team) {
        const std::uint32_t p0 = range_p_[static_cast<std::size_t>(r)], p1 = range_p_[static_cast<std::size_t>(r) + 1];
        for (std::size_t p = p0; p < p1; ++p) begin(p);
        for (int c = 0; c < T; ++c)
          for (const std::size_t k : cross_[static_cast<std::size_t>(c) * static_cast<std::size_t>(T) + static_cast<std::size_t>(r)])
            second(results[k], pk_.second(keys_[k]));
        for (std::size_t k = range_k_[static_cast<std::size_t>(r)]; k < range_k_[static_cast<std::size_t>(r) + 1]; ++k) {
          const std::uint32_t i = pk_.first(keys_[k]), j = pk_.second(keys_[k]);
          first(results[k], i);
          if (j < p1) second(results[k], j);
        }
        for (std::size_t p = p0; p < p1; ++p) end(p);
      }
    } catch (...) {
      if (!errors[static_cast<std::size_t>(t)]) errors[static_cast<std::size_t>(t)] = std::current_exception();
    }
  }
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace hgrid
