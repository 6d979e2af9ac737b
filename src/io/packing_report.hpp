// What `hgrid info FILE` prints about a packing: its quality figures
// (packing/generate.hpp, assess_packing) with the file's size, box and
// attributes, as JSON or as text.
#pragma once
#include <string>

#include "hgridlab/packing/generate.hpp"

namespace hgrid {

/// The report as JSON: file, n, d, box, tilt (null when upright), boundary,
/// the quality figures (overlaps, contacts, slab uniformity with its
/// counting noise), with `recorded_distribution` also the radii against the
/// file's recorded distribution (KS distance, p-value, histogram), and the
/// file's attributes.
std::string packing_report_json(const std::string& file, const Packing& p, const PackingQuality& q,
                                bool recorded_distribution);
/// The same figures as a few lines of text.
std::string packing_report_text(const std::string& file, const Packing& p, const PackingQuality& q,
                                bool recorded_distribution);

}  // namespace hgrid
