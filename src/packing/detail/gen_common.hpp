// Shared pieces of the packing generators: the random stream; progress lines
// (base/progress.hpp) and the unit ball (grid/geometry.hpp).
#pragma once
#include <cstdint>
#include <random>
#include <sstream>
#include <string>

#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/base/progress.hpp"

namespace hgrid::detail {

/// 53 random bits in [0, 1): the same stream on every platform.
class GenRng {
 public:
  explicit GenRng(std::uint64_t seed) : eng_(seed) {}
  double uniform() { return static_cast<double>(eng_() >> 11) * 0x1.0p-53; }
  std::uint64_t bits() { return eng_(); }
  /// The engine's full state as text (the standard's stream format), for
  /// resuming a generation exactly where it stopped.
  std::string state() const {
    std::ostringstream o;
    o << eng_;
    return o.str();
  }
  /// Restores state(); false (and the engine unchanged) if s is not one.
  bool restore(const std::string& s) {
    std::istringstream i(s);
    std::mt19937_64 e;
    if (!(i >> e)) return false;
    eng_ = e;
    return true;
  }

 private:
  std::mt19937_64 eng_;
};

}  // namespace hgrid::detail
