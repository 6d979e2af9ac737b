#include "bench/lammps_run.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace hgrid {
namespace {

bool starts_with(const std::string& s, const std::string& p) { return s.compare(0, p.size(), p) == 0; }

/// Second '|' field of a timing row "Neigh | min | avg | max | ...".
double timing_avg(const std::string& line) {
  std::stringstream ss(line);
  std::string field;
  std::getline(ss, field, '|');
  std::getline(ss, field, '|');  // min
  std::getline(ss, field, '|');  // avg
  return std::strtod(field.c_str(), nullptr);
}

}  // namespace

LammpsResult parse_lammps_log(const std::string& log) {
  LammpsResult r;
  std::stringstream ss(log);
  std::string line;
  bool timing = false;
  while (std::getline(ss, line)) {
    if (starts_with(line, "ERROR")) r.error = line;
    if (starts_with(line, "MPI task timing breakdown")) timing = true;
    if (timing && starts_with(line, "Neigh ")) r.neigh_seconds = timing_avg(line);
    if (timing && starts_with(line, "Comm ")) r.comm_seconds = timing_avg(line);
    if (starts_with(line, "Total # of neighbors =")) r.pairs = std::strtoull(line.c_str() + 22, nullptr, 10);
    if (starts_with(line, "Neighbor list builds =")) r.builds = std::strtoull(line.c_str() + 22, nullptr, 10);
  }
  r.ok = timing && r.error.empty();
  return r;
}

std::optional<std::string> find_lammps() {
  if (const char* e = std::getenv("HGRID_LMP"); e && *e) return std::string(e);
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  std::stringstream ss(path);
  std::string d;
  while (std::getline(ss, d, ':')) {
    const auto f = std::filesystem::path(d.empty() ? "." : d) / "lmp";
    std::error_code ec;
    if (std::filesystem::is_regular_file(f, ec) && ::access(f.c_str(), X_OK) == 0) return f.string();
  }
  return std::nullopt;
}

LammpsResult run_lammps(const std::string& lmp, const std::string& dir, const std::string& script) {
  const std::string log = "log." + script;
  const std::string cmd = "cd '" + dir + "' && OMP_NUM_THREADS=1 '" + lmp + "' -in '" + script + "' -log '" + log +
                          "' -screen none > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  std::ifstream f(dir + "/" + log);
  std::stringstream text;
  text << f.rdbuf();
  LammpsResult r = parse_lammps_log(text.str());
  if (rc != 0 && r.error.empty()) r.error = "lmp exited with status " + std::to_string(rc);
  if (rc != 0) r.ok = false;
  return r;
}

}  // namespace hgrid
