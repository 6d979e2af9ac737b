#include "hgridlab/io/provenance.hpp"

#include <ctime>

#include "hgridlab/grid/version.hpp"

namespace hgrid {

const char* version() { return HGRIDLAB_VERSION; }
const char* compiler_id() { return HGRID_COMPILER; }
const char* build_flags() { return HGRID_BUILD_FLAGS; }

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);  // not std::gmtime: its buffer is shared between threads
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace hgrid
