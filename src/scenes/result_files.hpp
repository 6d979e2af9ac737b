// Point results outside this process: one line of JSON per point (what MPI
// ranks send to rank 0) and the result files of a scene.
#pragma once
#include <string>
#include <vector>

#include "hgridlab/scenes/runner.hpp"

namespace hgrid {

/// A result as one line of JSON (no newline), every value exact.
std::string result_json_line(const PointResult& r);

/// Reads result_json_line() back, checked like any input: InputError naming
/// the field for a wrong type or range, or counts that do not add up (K is
/// the scene's).
PointResult result_from_json_line(const std::string& line, double K);

/// Writes `<stem>.h5` (raw counts per point and level, model values, the
/// parameters, seeds, scene text, git hash, compiler, timings) and `<stem>.csv`
/// (one row per point, named columns for gnuplot); both atomically.
void write_results(const std::string& stem, const Scene& scene, const std::vector<PointResult>& results);

}  // namespace hgrid
