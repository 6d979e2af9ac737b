// The data behind the paper's Figs. 2-10 (and our Fig. 13, accuracy against
// time), written as CSV with a "# key=value" header for gnuplot.
#pragma once
#include <functional>
#include <ostream>
#include <string>

namespace hgrid {

/// Receives one figure's data: its file name (figNN-*.csv) and CSV text.
/// Called from two threads at once; the caller writes the file.
using FigureSink = std::function<void(const std::string& name, const std::string& csv)>;

/// Computes the data of every figure (`only`: comma-separated figure numbers,
/// "" = all) and hands each CSV to `out`. Progress lines go to `log`. Runs on
/// two threads.
void write_model_figures(const FigureSink& out, const std::string& only, std::ostream& log);

}  // namespace hgrid
