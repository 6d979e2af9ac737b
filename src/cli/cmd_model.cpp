// Placeholder until the cost-model commands land (issue 3).
#include "cli/common.hpp"

namespace hgrid::cli {
void register_model_commands(CLI::App&) {}
}  // namespace hgrid::cli
