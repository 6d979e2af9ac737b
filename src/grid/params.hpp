// The one plain parameter struct of the HGrid.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "hgridlab/base/error.hpp"

namespace hgrid {

/// Cross-level search direction (docs/MODEL.md section 1): Top-Down tests a
/// particle against the levels below its own, Bottom-Up against those above.
enum class Search { top_down, bottom_up };

inline const char* to_string(Search s) { return s == Search::top_down ? "topdown" : "bottomup"; }

/// "topdown" or "bottomup"; anything else throws InputError naming `field`.
inline Search parse_search(std::string_view s, const std::string& field = "search") {
  if (s == "topdown") return Search::top_down;
  if (s == "bottomup") return Search::bottom_up;
  throw InputError(field, "must be 'topdown' or 'bottomup' (got '" + std::string(s) + "')");
}

/// The most levels a grid (and a cell-size method) may have. The figures'
/// widest case, linear sizes at omega = 1000, uses 184.
inline constexpr int kMaxLevels = 1000;

struct GridParams {
  /// Cell sizes s_1 < ... < s_L (L >= 1, strictly increasing, all > 0);
  /// s_L must be at least the largest particle diameter.
  std::vector<double> sizes;
  Search search = Search::top_down;
  /// Threads of the build and of for_each_pair (base/threads.hpp): 1 (the
  /// default: the callback is called from the calling thread only), n > 1,
  /// or 0 for all (OMP_NUM_THREADS, else every core). The pairs and the
  /// counters are the same for any number.
  int threads = 1;
};

}  // namespace hgrid
