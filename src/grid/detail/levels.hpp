// Geometry of one HGrid level and the flat cell directory behind it.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/grid/geometry.hpp"

namespace hgrid::detail {

inline constexpr std::uint64_t kEmptyKey = std::numeric_limits<std::uint64_t>::max();
inline constexpr std::uint64_t kNoBucket = std::numeric_limits<std::uint64_t>::max();
/// Cells per axis are limited so that a cell key (linear index) fits 63 bits.
inline constexpr std::int64_t kMaxCellsPerAxis = std::int64_t{1} << 21;
/// A level's non-empty cells are found through a rank directory (one bit per
/// cell plus a prefix count per 64 cells: ~1.5 bits per cell) while it has at
/// most this many cells per particle on it (plus a constant); sparser levels
/// use an open-addressing table of twice their particle count.
inline constexpr std::uint64_t kRankCellsPerParticle = 64;
inline constexpr std::uint64_t kRankMinCells = 1 << 16;

/// Particles per coarse bucket of the construction's first sorting step
/// (on average; the number of buckets per level is a power of two). Small
/// enough that a bucket sorts in the cache (~200 KB), large enough that the
/// first step writes to few streams: at N = 10^6, 3D, 512 to 65536 all
/// build within 10 % of each other, 4096 the fastest (54 vs 60 ns/particle
/// at 1024 and 58 at 65536).
inline constexpr std::uint64_t kCoarseBucket = 4096;

/// A small grid of one level (a linked cell) skips the two steps when it
/// holds at most kDirectParticles particles and has at most
/// kDirectCellsPerParticle cells per particle (plus kDirectMinCells): it is
/// sorted by one counting sort over its cells, its coarse buckets being the
/// cells themselves; the scatter's random writes stay in the cache (2 MB of
/// 3D spheres), and the cells' passes cost less than the radix passes they
/// replace. At N = 2 10^4, one 3D level of 12 000 cells (a pour's bed):
/// 0.46 -> 0.36 ms per rebuild. Several levels keep the two steps: counting
/// the particles of each level first cost a 2D grid of 10^4 particles on 5
/// levels 13 % of its build.
inline constexpr std::uint64_t kDirectParticles = std::uint64_t{1} << 16;
inline constexpr std::uint64_t kDirectCellsPerParticle = 2;
inline constexpr std::uint64_t kDirectMinCells = 4096;

inline std::uint64_t hash_key(std::uint64_t k) { return k * 0x9E3779B97F4A7C15ull; }

template <int D>
struct Level {
  std::array<double, D> s{};        // cell side per axis (equal unless fitted to a periodic box)
  std::array<std::int64_t, D> n{};  // cells per axis
  double s_min = 0;                 // smallest side: the insertion threshold for diameters
  bool ranked = true;               // rank directory (else hash table)
  bool small_periodic = false;      // some periodic axis has fewer than 3 cells
  std::uint64_t bucket_base = 0;    // first bucket of this level in the directory
  std::uint64_t buckets = 0;        // non-empty cells (one bucket each, in key order)
  std::uint64_t slots = 0;          // hashed: table size (a power of two)
  std::uint64_t word_base = 0;      // ranked: first bitmap word of this level
  std::uint64_t words = 0;          // ranked: bitmap words, cells / 64 + 1 (the last one
                                    // holds key == cells, so a rank is defined there too)
  std::uint64_t key_base = 0;       // hashed: first slot of its table in the key array
                                    // (and in the slot -> bucket array)
  int shift = 64;                   // hashed: 64 - log2(table size)

  std::uint64_t cells() const {
    std::uint64_t c = 1;
    for (int k = 0; k < D; ++k) c *= static_cast<std::uint64_t>(n[k]);
    return c;
  }
  /// Linear cell index with the LAST axis fastest, so that a row of cells
  /// along axis D-1 is a run of consecutive keys (and of sorted particles).
  std::uint64_t key(const std::array<std::int64_t, D>& c) const {
    std::uint64_t k = static_cast<std::uint64_t>(c[0]);
    for (int a = 1; a < D; ++a) k = k * static_cast<std::uint64_t>(n[a]) + static_cast<std::uint64_t>(c[a]);
    return k;
  }
  std::array<std::int64_t, D> coords(std::uint64_t key) const {
    std::array<std::int64_t, D> c{};
    for (int a = D - 1; a >= 0; --a) {
      c[a] = static_cast<std::int64_t>(key % static_cast<std::uint64_t>(n[a]));
      key /= static_cast<std::uint64_t>(n[a]);
    }
    return c;
  }
  /// Mapping M(x, h) of docs/MODEL.md section 1, clamped to the grid so that points
  /// on the far box face (walls) or rounded up to A (periodic) stay inside.
  std::int64_t cell_1d(double x, int a) const {
    const double c = std::floor(x / s[a]);
    if (!(c > 0)) return 0;
    if (c >= static_cast<double>(n[a])) return n[a] - 1;
    return static_cast<std::int64_t>(c);
  }
  std::array<std::int64_t, D> cell(const std::array<double, D>& x) const {
    std::array<std::int64_t, D> c{};
    for (int a = 0; a < D; ++a) c[a] = cell_1d(x[a], a);
    return c;
  }
};

/// Coordinates of increasing cell keys without a division per key: steps
/// along the row axis D-1 and carries, falling back to division for long jumps.
template <int D>
class KeyWalk {
 public:
  explicit KeyWalk(const Level<D>& L) : L_(L) {}
  const std::array<std::int64_t, D>& to(std::uint64_t key) {
    const std::uint64_t delta = key - key_;
    if (key < key_ || delta >= static_cast<std::uint64_t>(L_.n[D - 1])) {
      c_ = L_.coords(key);
    } else {
      c_[D - 1] += static_cast<std::int64_t>(delta);
      for (int a = D - 1; a > 0 && c_[a] >= L_.n[a]; --a) {
        c_[a] -= L_.n[a];
        ++c_[a - 1];
      }
    }
    key_ = key;
    return c_;
  }

 private:
  const Level<D>& L_;
  std::uint64_t key_ = 0;
  std::array<std::int64_t, D> c_{};
};

/// Lays out the levels for a box: fits periodic cells to the box (an integer
/// number of cells per axis, each at least the requested size unless the box
/// itself is smaller), and checks the box's sides and the cell count per
/// axis, into `levels` (whose capacity is reused; on a throw its content is
/// unspecified).
template <int D>
void make_levels(const std::vector<double>& sizes, const Extent<D>& box, Boundary b, std::vector<Level<D>>& levels) {
  for (int a = 0; a < D; ++a)
    if (!(std::isfinite(box[a]) && box[a] > 0))
      throw InputError("box", "side " + std::to_string(a + 1) + " must be finite and > 0");
  levels.assign(sizes.size(), Level<D>{});
  for (std::size_t h = 0; h < sizes.size(); ++h) {
    Level<D>& L = levels[h];
    L.s_min = std::numeric_limits<double>::infinity();
    for (int a = 0; a < D; ++a) {
      const double ratio = box[a] / sizes[h];
      if (ratio > static_cast<double>(kMaxCellsPerAxis))
        throw InputError("sizes", "level " + std::to_string(h + 1) + " would have " + std::to_string(ratio) +
                                      " cells per axis (at most " + std::to_string(kMaxCellsPerAxis) +
                                      " allowed); use larger cells");
      L.n[a] = static_cast<std::int64_t>(cells_per_axis(box[a], sizes[h], b));
      if (b == Boundary::periodic) {
        L.s[a] = box[a] / static_cast<double>(L.n[a]);
        if (L.n[a] < 3) L.small_periodic = true;
      } else {
        L.s[a] = sizes[h];
      }
      L.s_min = std::min(L.s_min, L.s[a]);
    }
  }
}

}  // namespace hgrid::detail
