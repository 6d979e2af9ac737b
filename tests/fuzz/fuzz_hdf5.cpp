// libFuzzer target: the HDF5 packing reader as the command-line tool runs it
// (in a child process with a time limit: libhdf5 itself crashes or hangs on
// some corrupt files). Any input gives a packing or an InputError. The child
// does the parsing, so coverage guidance is blind here: this target is a
// random mutation test of the seed files, and slow (a fork per input). A
// file libhdf5 loops on is cut off after kFuzzReadSeconds instead of the
// tool's 5 s (the parent's handling is the same), or most of the fuzzing
// time goes to waiting.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/packing_file.hpp"

constexpr double kFuzzReadSeconds = 0.05;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/hgridlab-fuzz-" + std::to_string(::getpid()) + ".h5";
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), size);
  try {
    hgrid::read_packing(path, hgrid::Isolation::child_process, kFuzzReadSeconds);
  } catch (const hgrid::InputError&) {
  }
  return 0;
}
