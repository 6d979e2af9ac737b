// The data behind the paper's Figs. 2-10 (and our Fig. 13, accuracy against
// time), written as CSV with a "# key=value" header for gnuplot.
#pragma once
#include <ostream>
#include <string>

namespace hgrid::detail {

/// Writes results files figNN-*.csv into `dir` (created if missing), each
/// atomically (temporary name, then rename). `only`: comma-separated figure
/// numbers ("" = all). Progress lines go to `log`. Runs on two threads.
void write_model_figures(const std::string& dir, const std::string& only, std::ostream& log);

}  // namespace hgrid::detail
