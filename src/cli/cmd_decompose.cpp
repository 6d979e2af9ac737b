// hgrid pairs|count FILE --sizes ... --decompose: the search split over the
// ranks of an MPI run (mpi/decomposed.hpp); rank 0 prints.
#include <malloc.h>

#include <climits>
#include <cstdlib>
#include <iostream>
#include <thread>

#include "common.hpp"
#include "hgridlab/mpi/comm.hpp"
#include "hgridlab/mpi/decomposed.hpp"

namespace hgrid::cli {

int threads_per_rank(int threads) {
  if (threads != 0 || mpi::size() == 1 || std::getenv("OMP_NUM_THREADS")) return threads;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, cores / mpi::local_size());
}

namespace {
/// A rank frees the part of the file it read once it has handed it out, and
/// then builds its grid: with glibc's defaults those arrays go back to the
/// system and the grid's come as fresh pages, each paid for by a page fault
/// on first touch (~0.1 s per rank at N = 10^7 on 2 ranks, a quarter of the
/// build). Kept in the heap instead, they are reused. One search per
/// process, so holding on to freed memory costs nothing after it.
void keep_freed_memory() {
#ifdef M_MMAP_MAX
  mallopt(M_MMAP_MAX, 0);                      // large blocks from the heap too
  mallopt(M_TRIM_THRESHOLD, INT_MAX);         // not handed back (below 2 GB)
#endif
}
}  // namespace

void run_decomposed_pairs(const std::string& file, const GridParams& g) {
  keep_freed_memory();
  std::vector<std::pair<std::uint64_t, std::uint64_t>> pairs;
  mpi::decomposed_search(file, g, false, &pairs);
  if (mpi::rank() != 0) return;
  PairWriter out;
  for (const auto& [i, j] : pairs) out(i, j);
}

void run_decomposed_count(const std::string& file, const GridParams& g, double K, bool as_json) {
  keep_freed_memory();
  const mpi::DecomposedCount c = mpi::decomposed_count(file, g, K);
  if (mpi::rank() == 0) std::cout << (as_json ? mpi::decomposed_count_json(c) : mpi::decomposed_count_text(c));
}

}  // namespace hgrid::cli
