// Where a result came from: the one provenance record every output carries.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace hgrid {

/// hgridlab's version (from the CMake project version).
const char* version();
/// The commit the binary was built from (with "-dirty" for a modified tree).
const char* git_hash();
/// Compiler, its version and the instruction set (-march).
const char* compiler_id();
/// The build type and compile flags that matter for results.
const char* build_flags();

/// Now, in UTC as ISO 8601 ("2026-12-04T05:06:40Z"): when a result was made.
std::string utc_now();

/// The provenance of a result, written as attributes or keys of every output.
struct Provenance {
  std::string version, git_hash, compiler, flags;
};

inline Provenance provenance() { return {version(), git_hash(), compiler_id(), build_flags()}; }

/// The record as named fields, in the order every output writes them
/// (HDF5 attributes, JSON keys, "# key=value" lines).
inline std::vector<std::pair<std::string, std::string>> provenance_fields() {
  return {{"version", version()}, {"git_hash", git_hash()}, {"compiler", compiler_id()}, {"build_flags", build_flags()}};
}

/// The record on one line ("version=... git_hash=... compiler=... build_flags=..."),
/// for text outputs.
inline std::string provenance_line() {
  std::string out;
  for (const auto& [k, v] : provenance_fields()) out += (out.empty() ? "" : " ") + k + "=" + v;
  return out;
}

}  // namespace hgrid
