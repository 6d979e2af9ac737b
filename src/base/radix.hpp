// Stable LSD radix sort of (key, id) pairs, used to sort particles by cell,
// or of keys alone (the DPM engine's contact pairs, into canonical order).
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

namespace hgrid::detail {

/// Sorts key[0, n) ascending, carrying id along (if WithId), stably (equal
/// keys keep their order). Only the low `bits` bits of the keys may be
/// non-zero. tkey and tid are scratch space of n entries each. Eight bits per
/// pass: each pass streams the input once and writes to 256 sequential
/// outputs; a pass whose digit is the same for every key is skipped.
template <bool WithId>
inline void radix_sort(std::uint64_t* key, std::uint32_t* id, std::uint64_t* tkey, std::uint32_t* tid, std::size_t n,
                       int bits) {
  std::uint64_t* const key0 = key;
  std::uint32_t* const id0 = id;
  for (int shift = 0; shift < bits; shift += 8) {
    std::array<std::size_t, 256> pos{};
    for (std::size_t i = 0; i < n; ++i) ++pos[(key[i] >> shift) & 255];
    if (std::find(pos.begin(), pos.end(), n) != pos.end()) continue;  // one digit: already ordered
    std::size_t sum = 0;
    for (auto& c : pos) {
      const std::size_t k = c;
      c = sum;
      sum += k;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = pos[(key[i] >> shift) & 255]++;
      tkey[j] = key[i];
      if constexpr (WithId) tid[j] = id[i];
    }
    std::swap(key, tkey);
    if constexpr (WithId) std::swap(id, tid);
  }
  if (key != key0) {
    std::copy(key, key + n, key0);
    if constexpr (WithId) std::copy(id, id + n, id0);
  }
}

inline void radix_sort_pairs(std::uint64_t* key, std::uint32_t* id, std::uint64_t* tkey, std::uint32_t* tid,
                             std::size_t n, int bits) {
  radix_sort<true>(key, id, tkey, tid, n, bits);
}

/// Keys only.
inline void radix_sort_keys(std::uint64_t* key, std::uint64_t* tkey, std::size_t n, int bits) {
  radix_sort<false>(key, nullptr, tkey, nullptr, n, bits);
}

}  // namespace hgrid::detail
