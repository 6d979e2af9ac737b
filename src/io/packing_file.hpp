// Packing files: read any supported format, write HDF5 with provenance.
#pragma once
#include <string>

#include "packing/packing.hpp"

namespace hgrid {

/// Reads a packing from an HDF5 file or a CSV file (by the .csv ending),
/// validates it (see validate()) and returns it. Throws InputError naming the
/// field that is wrong.
Packing read_packing(const std::string& path);

/// Writes a packing as HDF5 (datasets /positions N x d and /radii N; root
/// attributes d, box, boundary, the packing's own attributes and the
/// provenance record), atomically: a temporary file renamed into place.
void write_packing(const std::string& path, const Packing& p);

}  // namespace hgrid
