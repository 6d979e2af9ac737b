// Cell sizes for a packing chosen by the cost model (count/pairs --cells).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "hgrid/packing.hpp"
#include "hgrid/params.hpp"

namespace hgrid::cli {

struct SizeRequest {
  std::string method;  // linear|exponential|constant|optimal; empty: not requested
  std::optional<int> levels;
  double q = 1.0;
};

/// Sizes for the packing's own radii (empirical distribution) and packing fraction.
std::vector<double> model_sizes(const Packing& p, const SizeRequest& r, Search search, double K);

}  // namespace hgrid::cli
