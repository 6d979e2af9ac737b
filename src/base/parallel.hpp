// The grid's parallel loop (OpenMP; a plain loop without it) and a thread's
// place in its team.
#pragma once
#include <cstddef>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace hgrid::detail {

/// The calling thread's index in its team, and the team's size ({0, 1}
/// outside a parallel region or without OpenMP).
struct TeamSlot {
  int t, team;
};
inline TeamSlot team_slot() {
#if defined(_OPENMP)
  return {omp_get_thread_num(), omp_get_num_threads()};
#else
  return {0, 1};
#endif
}

/// Calls fn(i, t) for i in [0, n) on `threads` threads, t the calling
/// thread's index in [0, threads); the i are handed out one at a time. fn
/// must not throw (an exception cannot leave an OpenMP region): catch inside.
template <class Fn>
void parallel_for(int threads, std::size_t n, Fn&& fn) {
#if defined(_OPENMP)
  if (threads > 1 && n > 1) {
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (std::size_t i = 0; i < n; ++i) fn(i, omp_get_thread_num());
    return;
  }
#else
  (void)threads;
#endif
  for (std::size_t i = 0; i < n; ++i) fn(i, 0);
}

}  // namespace hgrid::detail
