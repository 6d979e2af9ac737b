// Wall-clock time of one contact search: best of repeated uncounted queries.
#pragma once
#include <cstdint>
#include <vector>

#include "model/time_model.hpp"
#include "grid/counters.hpp"
#include "packing/packing.hpp"
#include "grid/params.hpp"

namespace hgrid {

/// Repeat the uncounted query at least min_repeats times and until
/// min_seconds of query time have passed, but at most max_repeats times.
struct TimingOptions {
  int min_repeats = 3;
  int max_repeats = 50;
  double min_seconds = 0.2;
};

struct QueryTiming {
  Counters counts;            // one counted query (the same pairs)
  std::vector<double> sizes;  // cell sizes used (fitted to a periodic box)
  double query_seconds = 0;   // fastest uncounted query (find every pair)
  double build_seconds = 0;   // fastest construction of the grid
  double median_query_seconds = 0;
  int repeats = 0;
  BuildWork build_work;       // what the build did (terms of the time model)
};

/// Builds the grid and runs one counted query, then repeats build + uncounted
/// query (each timed on its own) and keeps the fastest of each: the
/// uncounted query is what a simulation runs, the counted one gives the
/// cell accesses and checks that the cost model predicts.
QueryTiming time_query(const Packing& p, const GridParams& g, const TimingOptions& opt = {});

}  // namespace hgrid
