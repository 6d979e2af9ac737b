// The one plain parameter struct of the HGrid.
#pragma once
#include <vector>

namespace hgrid {

/// Cross-level search direction (MODEL.md section 1): Top-Down tests a
/// particle against the levels below its own, Bottom-Up against those above.
enum class Search { top_down, bottom_up };

inline const char* to_string(Search s) { return s == Search::top_down ? "topdown" : "bottomup"; }

struct GridParams {
  /// Cell sizes s_1 < ... < s_L (L >= 1, strictly increasing, all > 0);
  /// s_L must be at least the largest particle diameter.
  std::vector<double> sizes;
  Search search = Search::top_down;
};

}  // namespace hgrid
