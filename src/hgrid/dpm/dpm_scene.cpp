#include "hgrid/dpm/dpm_scene.hpp"

#include "hgrid/error.hpp"

namespace hgrid::dpm {

void run_dpm_scene(const std::string&, const std::string&, const RunOptions&, bool) {
  throw InputError("kind", "DPM scenes are not available in this build yet");
}

}  // namespace hgrid::dpm
