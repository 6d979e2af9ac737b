// How a generated packing records its generation in its attributes: the
// names of an equilibration's state and the stationarity series (what
// resuming and the identity checks read back; packing/identity.cpp).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "hgridlab/packing/packing.hpp"

namespace hgrid::detail {

/// Bump when a change alters the packings a spec produces (invalidates caches).
/// 2: the growth + FIRE route sums forces over sorted neighbour lists, so that
/// its packings no longer depend on the HGrid's pair order (version 1's did,
/// and changed with the query's traversal). 3: growth steps of 2 % relaxed
/// to 5e-3 (were 0.5 % and 2e-3). 4: FIRE's masses are the spheres'
/// stiffness sums (kFireMassFloor; were one).
inline constexpr int kGeneratorVersion = 4;

/// Names of the attributes that carry an equilibration's state.
inline constexpr const char* kChainAttr = "equilibration_chain";
inline constexpr const char* kRngAttr = "equilibration_rng_state";
inline constexpr const char* kTallyAttrs[4] = {"equilibration_moves_accepted", "equilibration_moves_proposed",
                                        "equilibration_swaps_accepted", "equilibration_swaps_proposed"};
/// stop = stationary: the observable's samples so far (every
/// kStationarySampleSweeps sweeps, %.17g, comma separated), what resuming
/// needs to take the same decision.
inline constexpr const char* kSeriesAttr = "stationarity_series";

inline std::string join_series(const std::vector<double>& v) {
  std::string out;
  char buf[32];
  for (double x : v) {
    std::snprintf(buf, sizeof buf, "%.17g", x);
    if (!out.empty()) out += ',';
    out += buf;
  }
  return out;
}

/// The series recorded in p, or nothing when it is absent or unreadable.
inline std::optional<std::vector<double>> recorded_series(const Packing& p) {
  const auto it = p.str_attrs.find(kSeriesAttr);
  if (it == p.str_attrs.end()) return std::nullopt;
  std::vector<double> v;
  const std::string& t = it->second;
  std::size_t at = 0;
  while (at < t.size()) {
    const std::size_t end = std::min(t.find(',', at), t.size());
    try {
      std::size_t used = 0;
      const std::string item = t.substr(at, end - at);
      v.push_back(std::stod(item, &used));
      if (used != item.size() || !std::isfinite(v.back())) return std::nullopt;
    } catch (const std::exception&) {
      return std::nullopt;
    }
    at = end + 1;
  }
  return v;
}

/// Whether p is a placement (generated without equilibration).
inline bool is_placement(const Packing& p) {
  const auto eq = p.num_attrs.find("equilibrate");
  return eq != p.num_attrs.end() && eq->second == 0;
}

}  // namespace hgrid::detail
