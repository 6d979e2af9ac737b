// The packing cache: every packing is generated once and kept on disk.
#pragma once
#include <string>

#include "hgridlab/packing/generate.hpp"

namespace hgrid {

/// dir/<16 hex digits of an FNV-1a hash of packing_key(spec)>.h5
std::string packing_cache_path(const PackingSpec& spec, const std::string& dir);

/// dir/<hash of equilibration_chain_key(spec)>.resume.h5: the furthest stage
/// reached of one equilibration (any sweeps), with its generator state.
std::string equilibration_resume_path(const PackingSpec& spec, const std::string& dir);

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
