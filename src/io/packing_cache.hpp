// The packing cache: every packing is generated once and kept on disk, under
// the name its identity gives it (packing/identity.hpp).
#pragma once
#include <string>

#include "hgridlab/packing/generate.hpp"
#include "hgridlab/packing/identity.hpp"

namespace hgrid {

/// Reads the cached packing for spec if it exists and passes
/// packing_mismatch(); otherwise generates it and writes it atomically to
/// packing_cache_path(spec, dir). An equilibration resumes from the resume
/// file when that holds the same packing at no more than spec.sweeps, and
/// leaves there the furthest stage reached: checkpoints of a long run
/// (generate_packing's) and its end. A run killed part-way, or one asking
/// for more sweeps than an earlier one, continues where that stopped; the
/// packing is the uninterrupted run's, bit for bit.
Packing cached_packing(const PackingSpec& spec, const std::string& dir);

}  // namespace hgrid
