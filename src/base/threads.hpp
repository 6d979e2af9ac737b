// How many threads a grid uses, and the callback contract when it uses more
// than one (OpenMP from the compiler; without it every grid runs on one).
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <utility>

#include "hgridlab/base/error.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace hgrid {

/// True when this build runs grids on several threads (compiled with OpenMP).
inline constexpr bool kHaveThreads =
#if defined(_OPENMP)
    true;
#else
    false;
#endif

/// The number of threads meant by a `threads` parameter: n itself if n >= 1;
/// 0 means all: OpenMP's default team size, which follows OMP_NUM_THREADS
/// (else the number of cores). Always 1 in a build without OpenMP.
inline int resolve_threads(int n) {
#if defined(_OPENMP)
  return n >= 1 ? n : omp_get_max_threads();
#else
  (void)n;
  return 1;
#endif
}

/// The most threads a `threads` parameter may ask for.
inline constexpr int kMaxThreads = 1024;

/// A `threads` value as given by a user: 0 (all cores) or 1 to kMaxThreads,
/// else an InputError naming `field`. Returns the value.
inline int check_threads(int n, const std::string& field = "threads") {
  if (n < 0 || n > kMaxThreads)
    throw InputError(field, "must be 0 (all cores) or 1 to " + std::to_string(kMaxThreads) + " (got " +
                                std::to_string(n) + ")");
  return n;
}

/// The callback of a query run on T threads. If it can be called as
/// f(t, i, j), it is, with t in [0, T) the index of the calling thread: two
/// calls with the same t never overlap, so per-thread buffers indexed by t
/// need no lock. Otherwise it is called as f(i, j), concurrently from several
/// threads when T > 1: it must be safe to call so (atomics, a lock). With
/// T = 1 every call comes from the calling thread, t = 0.
template <class F>
inline constexpr bool kTakesThreadIndex = std::is_invocable_v<F&, int, std::uint32_t, std::uint32_t>;

/// A pair as a batch hands it over: input indices, first < second.
using IndexPair = std::pair<std::uint32_t, std::uint32_t>;
/// A callback object with a member pairs(std::span<const IndexPair>) (or,
/// taking the thread index, pairs(t, span)) is handed the pairs in batches
/// of up to 64, in the order single calls would have come, one call per
/// batch instead of one per pair (a contact list's build stores each batch
/// in one go: -5 to -9 % on a pour's bed). Its f(i, j) is then not called by a
/// grid's pair queries.
template <class F>
inline constexpr bool kTakesBatches = requires(F& f, std::span<const IndexPair> s) { f.pairs(s); };
template <class F>
inline constexpr bool kTakesBatchesWithThread = requires(F& f, int t, std::span<const IndexPair> s) { f.pairs(t, s); };

}  // namespace hgrid
