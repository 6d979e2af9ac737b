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

  // How this implementation spends its time beyond the paper's two counts
  // (docs/MODEL.md section 9, the time model): the same-level phase visits
  // each non-empty cell once; a cross-level search walks its box a row of
  // cells (along the last axis) at a time, or, when the box holds more
  // cells than the searched level holds particles, scans that level's
  // particles instead. A level with many more cells than particles keeps
  // its non-empty cells in a hash table, where every cell of a stencil or
  // box is one look-up (a probe). L x L where marked, like the matrices above.
  std::uint64_t occupied_cells = 0;           // non-empty cells visited (same-level phase)
  std::uint64_t searches = 0;                 // cross-level searches (one per particle and level searched)
  std::uint64_t rows = 0;                     // rows of cells walked by the cross-level searches
  std::uint64_t scanned = 0;                  // particles scanned instead of walking a box
  std::uint64_t probes = 0;                   // cells looked up one by one in a hashed level's table
  /// Narrow-phase checks of candidates gathered from short ranges (at most
  /// 4 particles) into one index list and tested without a branch; the
  /// others test contiguous runs of the sorted particles.
  std::uint64_t list_checks = 0;
  /// Contiguous runs tested (a loop each: the rest of a particle's own
  /// cell, a range of more than 4, a hashed level's cell in a box).
  std::uint64_t runs = 0;
  std::vector<std::uint64_t> occupied_by_level;  // L
  std::vector<std::uint64_t> searches_by_level;  // L x L
  std::vector<std::uint64_t> rows_by_level;      // L x L

  /// The paper's cost T = T_cd + K * T_ca (Eq. 27) for these counts.
  double cost(double K) const {
    return static_cast<double>(narrow_phase_checks) + K * static_cast<double>(cell_accesses);
  }
  /// Adds another part of the same query's counts (a thread's), element by
  /// element; levels and particles per level are the query's, kept as they are.
  void add(const Counters& o) {
    cell_accesses += o.cell_accesses;
    narrow_phase_checks += o.narrow_phase_checks;
    contacts += o.contacts;
    occupied_cells += o.occupied_cells;
    searches += o.searches;
    rows += o.rows;
    scanned += o.scanned;
    probes += o.probes;
    list_checks += o.list_checks;
    runs += o.runs;
    const auto sum = [](std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b) {
      for (std::size_t k = 0; k < a.size() && k < b.size(); ++k) a[k] += b[k];
    };
    sum(accesses_by_level, o.accesses_by_level);
    sum(checks_by_level, o.checks_by_level);
    sum(occupied_by_level, o.occupied_by_level);
    sum(searches_by_level, o.searches_by_level);
    sum(rows_by_level, o.rows_by_level);
  }
  std::uint64_t particles() const {
    std::uint64_t n = 0;
    for (auto v : particles_per_level) n += v;
    return n;
  }
};

/// Compile-time counting policies for HGrid::query. `tests`: whether the
/// candidates are tested (and the overlapping pairs handed to the callback).
struct Counted {
  static constexpr bool enabled = true, tests = true;
};
struct Uncounted {
  static constexpr bool enabled = false, tests = true;
};
/// The pairs alone: as Uncounted, and the returned Counters are left
/// empty (not even particles_per_level), so that a query on one thread
/// allocates nothing (a contact list's rebuilds, step after step).
struct PairsOnly {
  static constexpr bool enabled = false, tests = true;
};
/// The counts alone: every field Counted counts, counted the same, but no
/// candidate is tested, so the callback is never called and `contacts`
/// stays 0. The cost T = T_cd + K T_ca (Counters::cost) does not depend on
/// the tests' outcomes: an observable sampled often (an equilibration's
/// T/N) gets it for the price of the cell visits.
struct CountsOnly {
  static constexpr bool enabled = true, tests = false;
};

}  // namespace hgrid
