// The one table of a Measurement's fields: name, unit, meaning and value.
// The CLI's JSON and text, the scene result files (journal, CSV, HDF5),
// the Python dict and the benchmarks' counters are all written from it, so
// a quantity has one name in every output (docs/MEASUREMENT.md lists it).
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "hgridlab/measure/measurement.hpp"

namespace hgrid {

/// A field's value: null (not measured), true/false, a whole number, a
/// number, text, or a list.
using FieldValue = std::variant<std::monostate, bool, std::int64_t, std::uint64_t, double, std::string,
                                std::vector<double>, std::vector<std::uint64_t>>;

struct MeasurementField {
  const char* name;
  const char* unit;     // "1" for pure numbers and counts, "" for text
  const char* meaning;
  FieldValue (*value)(const Measurement&);
};

/// Every field, in the order reports print them.
std::span<const MeasurementField> measurement_fields();
/// The field called `name`; std::logic_error for a name the table lacks (a
/// report asking for a field that does not exist is a bug, not bad input).
const MeasurementField& measurement_field(std::string_view name);

/// One JSON object: the fields named (all when `names` is empty), in table
/// order; NaN and empty text as null. indent < 0: one line.
std::string measurement_json(const Measurement& m, std::span<const std::string_view> names = {}, int indent = 2);

/// The text form (`hgrid count`): the packing and grid in one line, a table
/// per level (its particles, accesses, checks and the models' expected
/// checks), the totals, and the timings and time model when measured.
std::string measurement_text(const Measurement& m);

}  // namespace hgrid
