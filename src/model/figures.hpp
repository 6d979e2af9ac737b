// The data behind the paper's Figs. 2-10 (and our Fig. 13, accuracy against
// time), written as CSV with a "# key=value" header for gnuplot.
#pragma once
#include <functional>
#include <optional>
#include <ostream>
#include <string>

#include "hgridlab/model/time_model.hpp"

namespace hgrid {

/// Receives one figure's data: its file name (figNN-*.csv) and CSV text.
/// Called from two threads at once; the caller writes the file.
using FigureSink = std::function<void(const std::string& name, const std::string& csv)>;

/// Computes the data of every figure (`only`: comma-separated figure numbers,
/// "" = all) and hands each CSV to `out`. Progress lines go to `log`. Runs on
/// two threads.
/// `time`: a machine's 3D time-model coefficients (e.g. the committed
/// results/calibration.json); with them Fig. 13 gains the time-optimal sizes
/// (time_optimal_sizes for kFig13Particles particles), whose T lies above
/// the count optimum by what saving seconds costs in counts.
void write_model_figures(const FigureSink& out, const std::string& only, std::ostream& log,
                         const std::optional<TimeCoefficients>& time = std::nullopt);

/// Particles the time-optimal sizes of Fig. 13 are chosen for.
inline constexpr double kFig13Particles = 1e6;

}  // namespace hgrid
