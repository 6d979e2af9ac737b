// libFuzzer target: the text particle readers (tables, LAMMPS data and dump
// files). Any input either gives a particle set (and a packing, or an
// InputError making one) or an InputError; nothing else.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/particle_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    hgrid::to_packing(hgrid::parse_particles(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz"),
                      "fuzz");
  } catch (const hgrid::InputError&) {
  }
  return 0;
}
