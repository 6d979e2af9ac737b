#include "cli/grid_sizes.hpp"

#include "hgrid/error.hpp"

namespace hgrid::cli {

std::vector<double> model_sizes(const Packing&, const SizeRequest&, Search, double) {
  throw InputError("cells", "the cost model is not available in this build yet; use --sizes");
}

}  // namespace hgrid::cli
