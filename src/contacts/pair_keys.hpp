// Contact pairs in canonical order, (i, j) ascending: a pair (i < j, input
// indices) packed into one 64-bit key, i in the high bits, so that a radix
// sort of the keys puts any grid's pairs into one order. Sums over pairs in
// that order (the DPM engine's forces, the generator's FIRE relaxation) do
// not depend on the grid's cell sizes, levels, search direction or traversal.
#pragma once
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hgridlab/base/radix.hpp"

namespace hgrid::detail {

class PairKeys {
 public:
  /// For input indices below n.
  explicit PairKeys(std::size_t n) : bits_(std::max(1, static_cast<int>(std::bit_width(n > 0 ? n - 1 : 0)))) {}
  std::uint64_t key(std::uint32_t i, std::uint32_t j) const { return (std::uint64_t{i} << bits_) | j; }
  std::uint32_t first(std::uint64_t key) const { return static_cast<std::uint32_t>(key >> bits_); }
  /// Bits of one index in a key (a key has twice as many).
  int bits() const { return bits_; }
  std::uint32_t second(std::uint64_t key) const {
    return static_cast<std::uint32_t>(key & ((std::uint64_t{1} << bits_) - 1));
  }
  /// Sorts keys ascending (tmp: scratch, resized here).
  void sort(std::vector<std::uint64_t>& keys, std::vector<std::uint64_t>& tmp) const {
    tmp.resize(keys.size());
    radix_sort_keys(keys.data(), tmp.data(), keys.size(), 2 * bits_);
  }

 private:
  int bits_;
};

}  // namespace hgrid::detail
