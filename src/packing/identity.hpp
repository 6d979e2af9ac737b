// A packing's identity: what makes two generated packings the same one
// (its key, recorded in the file), why a file is not the packing a spec
// asks for, whether an equilibration can be resumed from it, and the names
// the packing cache gives it (the cache itself, reading and writing those
// files, is io/packing_cache.hpp).
#pragma once
#include <cstdint>
#include <string>

#include "hgridlab/packing/generate.hpp"
#include "hgridlab/packing/packing.hpp"

namespace hgrid {

/// The one identity of a packing: every field of spec that changes the
/// packing, and the generator version (stored as the "cache_key" attribute).
std::string packing_key(const PackingSpec& spec);

/// stop = stationary: the fewest samples of T/N before the test may pass,
/// set by the moves (packing/detail/gen_stationary.hpp); part of the key.
std::size_t stationary_floor(const PackingSpec& spec);

/// packing_key without the sweeps: the same for every stage of one
/// equilibration (stored as the "equilibration_chain" attribute).
std::string equilibration_chain_key(const PackingSpec& spec);

/// Why p is not the packing spec generates ("" when it is): its recorded key,
/// N, d, boundary, achieved nu, and (excluded volume) its overlaps.
std::string packing_mismatch(const Packing& p, const PackingSpec& spec);

/// Why generate_packing(spec, &from) cannot resume from `from` ("" when it
/// can): neither an equilibration of the same packing nor its placement, one
/// without the recorded state, one further than spec.sweeps, or one failing
/// packing_mismatch.
std::string resume_mismatch(const Packing& from, const PackingSpec& spec);

/// Monte Carlo sweeps a packing records (0 when not equilibrated).
std::uint64_t equilibration_sweeps_done(const Packing& p);

/// dir/<16 hex digits of an FNV-1a hash of packing_key(spec)>.h5
std::string packing_cache_path(const PackingSpec& spec, const std::string& dir);

/// dir/<hash of equilibration_chain_key(spec)>.resume.h5: the furthest stage
/// reached of one equilibration (any sweeps), with its generator state.
std::string equilibration_resume_path(const PackingSpec& spec, const std::string& dir);

}  // namespace hgrid
