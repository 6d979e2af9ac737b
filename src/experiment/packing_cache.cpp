#include "experiment/packing_cache.hpp"

#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "grid/error.hpp"
#include "io/atomic_file.hpp"
#include "io/packing_file.hpp"

namespace hgrid {

std::string packing_cache_path(const PackingSpec& s, const std::string& dir) {
  std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a, 64 bit
  for (unsigned char c : packing_key(s)) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, h);
  return (std::filesystem::path(dir) / (std::string(buf) + ".h5")).string();
}

Packing cached_packing(const PackingSpec& s, const std::string& dir) {
  const std::string path = packing_cache_path(s, dir);
  if (std::filesystem::exists(path)) {
    std::string problem;
    try {
      Packing p = read_packing(path);
      problem = packing_mismatch(p, s);
      if (problem.empty()) return p;
    } catch (const InputError& e) {
      problem = e.what();
    }
    std::cerr << "hgrid: cached packing " << path << " rejected (" << problem << "); regenerating\n";
  }
  Packing p = generate_packing(s);
  std::filesystem::create_directories(dir);
  remove_stale_temporaries(dir, kStaleTemporaryAge);
  write_packing(path, p);
  return p;
}

}  // namespace hgrid
