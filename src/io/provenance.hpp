// Where a result came from: the one provenance record every output carries.
#pragma once
#include <string>

namespace hgrid {

/// hgridlab's version (from the CMake project version).
const char* version();
/// The commit the binary was built from (with "-dirty" for a modified tree).
const char* git_hash();
/// Compiler, its version and the instruction set (-march).
const char* compiler_id();
/// The build type and compile flags that matter for results.
const char* build_flags();

/// The provenance of a result, written as attributes or keys of every output.
struct Provenance {
  std::string version, git_hash, compiler, flags;
};

inline Provenance provenance() { return {version(), git_hash(), compiler_id(), build_flags()}; }

}  // namespace hgrid
