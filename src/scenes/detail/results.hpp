// Scene results: JSON (journal, --json) and the HDF5 + CSV result files.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "hgridlab/scenes/result_files.hpp"
#include "hgridlab/scenes/runner.hpp"

namespace hgrid::detail {

nlohmann::json result_to_json(const PointResult& r);
/// Reads a result back (the resume journal), checking every value like any
/// input: InputError naming the field for a wrong type, sign or range.
PointResult result_from_json(const nlohmann::json& j);

/// Checks a result's counts against each other: one entry per level (sizes,
/// particles) or per pair of levels (accesses, checks), the lists adding up
/// to n, accesses and checks, and T/N equal to
/// (checks + K accesses) / n. Throws InputError naming the field.
void check_result(const PointResult& r, double K);
}  // namespace hgrid::detail
