// The work an HGrid query did, in the paper's terms (docs/MODEL.md section 1).
#pragma once
#include <cstdint>
#include <vector>

namespace hgrid {

/// Returned by value from every counted query; the same struct feeds tests,
/// benchmarks and the comparison with the cost model. Matrices are L x L,
/// row = level of the particle, column = level searched (index h * L + j).
struct Counters {
  std::uint64_t cell_accesses = 0;
  std::uint64_t narrow_phase_checks = 0;
  std::uint64_t contacts = 0;
  int levels = 0;
  std::vector<std::uint64_t> particles_per_level;
  std::vector<std::uint64_t> accesses_by_level;
  std::vector<std::uint64_t> checks_by_level;

  /// The paper's cost T = T_cd + K * T_ca (Eq. 27) for these counts.
  double cost(double K) const {
    return static_cast<double>(narrow_phase_checks) + K * static_cast<double>(cell_accesses);
  }
  std::uint64_t particles() const {
    std::uint64_t n = 0;
    for (auto v : particles_per_level) n += v;
    return n;
  }
};

/// Compile-time counting policies for HGrid::query.
struct Counted { static constexpr bool enabled = true; };
struct Uncounted { static constexpr bool enabled = false; };

}  // namespace hgrid
