// The packing cache: every packing is generated once and kept on disk.
#pragma once
#include <string>

#include "packing/generate.hpp"

namespace hgrid {

/// dir/<16 hex digits of an FNV-1a hash of packing_key(spec)>.h5
std::string packing_cache_path(const PackingSpec& spec, const std::string& dir);

/// Reads the cached packing for spec if it exists and passes
/// packing_mismatch(); otherwise generates it and writes it atomically to
/// packing_cache_path(spec, dir).
Packing cached_packing(const PackingSpec& spec, const std::string& dir);

}  // namespace hgrid
