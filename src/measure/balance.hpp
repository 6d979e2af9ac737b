// Load balance of the threaded query beyond this machine, by simulation: the
// counted work of every piece of the actual decomposition for P threads
// (HGrid::counted_pieces), priced by this machine's time model (or by the
// paper's T without one), handed out one at a time to P simulated threads as
// the dynamic schedule does.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hgridlab/grid/params.hpp"
#include "hgridlab/model/time_model.hpp"
#include "hgridlab/packing/packing.hpp"

namespace hgrid {

struct Balance {
  int threads = 0;
  std::size_t pieces = 0;
  /// Simulated wall time over the ideal (total work / threads), minus 1:
  /// 0.05 means the slowest thread ends 5 % after a perfect split would.
  double imbalance = 0;
  /// The largest piece's share of the total work, times threads: above 1, that
  /// piece alone is longer than a perfect split's time.
  double largest_piece = 0;
};

/// The work of a piece in the simulation: the time model's predicted seconds
/// of its query terms when `coef` is given, else T = checks + K accesses.
struct BalanceCost {
  std::optional<TimeCoefficients> coef;
  double K = 0.2;
  std::string name() const { return coef ? "time model (seconds)" : "T = checks + K accesses"; }
};

/// Simulated balance of the query of p with params g (its threads ignored)
/// for each number of threads in `threads`; the search direction is g's.
std::vector<Balance> simulate_balance(const Packing& p, const GridParams& g, std::span<const int> threads,
                                      const BalanceCost& cost);

/// The dynamic schedule itself: pieces of the given costs, in order, each to
/// the simulated thread that becomes free first; returns the makespan.
double simulated_makespan(std::span<const double> costs, int threads);

}  // namespace hgrid
