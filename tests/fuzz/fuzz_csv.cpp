// libFuzzer target: the CSV packing reader. Any input either gives a valid
// packing or an InputError; nothing else (no crash, no other exception).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/packing_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    hgrid::parse_packing_csv(in, "fuzz.csv");
  } catch (const hgrid::InputError&) {
  }
  return 0;
}
