#include "hgridlab/io/provenance.hpp"

#include "hgridlab/grid/version.hpp"

namespace hgrid {

const char* version() { return HGRIDLAB_VERSION; }
const char* compiler_id() { return HGRID_COMPILER; }
const char* build_flags() { return HGRID_BUILD_FLAGS; }

}  // namespace hgrid
