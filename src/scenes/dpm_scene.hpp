// DPM scenes (kind = "dpm"): a discrete-element run driven by a scene file.
#pragma once
#include <string>

#include "hgridlab/scenes/runner.hpp"

namespace hgrid::dpm {

/// Runs a DPM scene at a scale and writes its results; returns its summary
/// for stdout: with `json` as JSON, else one line. Throws InputError naming
/// a bad key or value.
std::string run_dpm_scene(const std::string& path, const std::string& scale, const RunOptions& opt, bool json);

}  // namespace hgrid::dpm
