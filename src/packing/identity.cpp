// A packing's identity (packing/identity.hpp).
#include "hgridlab/packing/identity.hpp"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "hgridlab/base/error.hpp"
#include "hgridlab/packing/detail/gen_common.hpp"
#include "hgridlab/packing/detail/gen_equilibrate.hpp"
#include "hgridlab/packing/detail/gen_record.hpp"
#include "hgridlab/packing/detail/gen_relax.hpp"
#include "hgridlab/packing/detail/gen_stationary.hpp"

namespace hgrid {

using detail::is_placement;
using detail::kGeneratorVersion;
using detail::kChainAttr;
using detail::kRngAttr;
using detail::kTallyAttrs;
using detail::recorded_series;

std::size_t stationary_floor(const PackingSpec& s) {
  return detail::stationary_min_samples(s.moves == EquilibrationMoves::event_chain);
}

std::string packing_key(const PackingSpec& s) {
  std::string k = "hgridlab-packing v" + std::to_string(kGeneratorVersion) + " d=" + std::to_string(s.d) +
                  " n=" + std::to_string(s.n) + " nu=" + format_number(s.nu) + " dist=" + s.dist;
  k += s.dist == "lognormal" ? " sigma=" + format_number(s.sigma) : " alpha=" + format_number(s.alpha);
  k += " omega=" + format_number(s.omega) + " boundary=" + to_string(s.boundary) + " placement=" + to_string(s.placement) +
       (s.placement == Placement::excluded && s.method != ExcludedMethod::automatic
            ? std::string(" method=") + to_string(s.method)
            : std::string()) +
       " seed=" + std::to_string(s.seed) + " equilibrate=" +
       (s.equilibrate ? std::string(s.moves == EquilibrationMoves::event_chain ? "1 event-chain" : "1 checkerboard") +
                            (s.stop == EquilibrationStop::stationary ? " until=" + detail::stationarity_rule(s.stationary_tol, stationary_floor(s)) : std::string()) +
                            " sweeps=" + std::to_string(s.sweeps)
                      : "0");
  return k;
}

std::string equilibration_chain_key(const PackingSpec& s) {
  PackingSpec base = s;
  base.sweeps = 0;
  const std::string k = packing_key(base);
  return k.substr(0, k.rfind(" sweeps="));
}

std::string packing_mismatch(const Packing& p, const PackingSpec& s) {
  const auto key = p.str_attrs.find("cache_key");
  if (key == p.str_attrs.end() || key->second != packing_key(s)) return "its parameters differ";
  if (p.size() != s.n || p.d != s.d || p.boundary != s.boundary) return "N, d or boundary differ";
  if (std::abs(p.packing_fraction() / s.nu - 1) > kNuRelTol) return "its nu differs";
  // Event chains move spheres kChainShrink smaller than the packing's.
  const double tol = s.equilibrate && s.moves == EquilibrationMoves::event_chain ? detail::kChainShrink
                                                                               : detail::kFinalOverlapTol;
  if (excludes_volume(s.placement) && assess_packing(p, nullptr).max_rel_overlap > tol)
    return "it has overlaps above tolerance";
  return "";
}

std::string resume_mismatch(const Packing& from, const PackingSpec& s) {
  if (!s.equilibrate) return "the requested packing is not equilibrated";
  if (is_placement(from)) {  // sweep 0 of every equilibration of it
    if (!from.str_attrs.count(kRngAttr)) return "it records no generator state (placed by an older hgrid)";
    PackingSpec placed = s;
    placed.equilibrate = false;
    return packing_mismatch(from, placed);
  }
  const auto chain = from.str_attrs.find(kChainAttr);
  if (chain == from.str_attrs.end() || !from.str_attrs.count(kRngAttr) || !from.num_attrs.count("equilibration_sweeps"))
    return "it records no resumable equilibration";
  if (chain->second != equilibration_chain_key(s)) return "its parameters differ";
  for (const char* a : kTallyAttrs)
    if (!from.num_attrs.count(a)) return "it records no resumable equilibration";
  const double done = from.num_attrs.at("equilibration_sweeps");
  if (!(done >= 1 && done <= s.sweeps && done == std::floor(done))) return "it is further than the requested sweeps";
  if (s.stop == EquilibrationStop::stationary) {
    const auto series = recorded_series(from);
    if (!series || series->size() != static_cast<std::size_t>(done) / detail::kStationarySampleSweeps)
      return "it records no stationarity series for its sweeps";
    if (detail::test_stationary(*series, s.stationary_tol, stationary_floor(s)).stationary) return "it ended its run (stationary)";
  }
  PackingSpec at = s;
  at.sweeps = static_cast<int>(done);
  return packing_mismatch(from, at);
}

std::uint64_t equilibration_sweeps_done(const Packing& p) {
  const auto it = p.num_attrs.find("equilibration_sweeps");
  return it == p.num_attrs.end() ? 0 : static_cast<std::uint64_t>(it->second);
}

namespace {
std::string hashed_name(const std::string& key, const char* suffix) {
  std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a, 64 bit
  for (const unsigned char c : key) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, h);
  return std::string(buf) + suffix;
}
}  // namespace

std::string packing_cache_path(const PackingSpec& spec, const std::string& dir) {
  return (std::filesystem::path(dir) / hashed_name(packing_key(spec), ".h5")).string();
}

std::string equilibration_resume_path(const PackingSpec& spec, const std::string& dir) {
  return (std::filesystem::path(dir) / hashed_name(equilibration_chain_key(spec), ".resume.h5")).string();
}

}  // namespace hgrid
