#include "bench/lammps_run.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace hgrid {
namespace {

bool starts_with(const std::string& s, const std::string& p) { return s.compare(0, p.size(), p) == 0; }

/// Field `k` (1: min, 2: avg, 3: max) of a timing row "Neigh | min | avg | max | ...".
double timing_field(const std::string& line, int k) {
  std::stringstream ss(line);
  std::string field;
  for (int i = 0; i <= k; ++i) std::getline(ss, field, '|');
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
    if (timing && starts_with(line, "Neigh ")) r.neigh_seconds = timing_field(line, 2), r.neigh_max_seconds = timing_field(line, 3);
    if (timing && starts_with(line, "Comm ")) r.comm_seconds = timing_field(line, 2);
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

LammpsResult run_lammps(const std::string& lmp, const std::string& dir, const std::string& script, int ranks) {
  const std::string log = "log." + script;
  std::string launcher;
  if (ranks > 1) {
    const char* m = std::getenv("HGRID_MPIRUN");
    launcher.append("'").append(m && *m ? m : "mpirun").append("' -np ").append(std::to_string(ranks));
    launcher.append(" --oversubscribe ").append(::geteuid() == 0 ? "--allow-run-as-root " : "");
  }
  const std::string cmd = "cd '" + dir + "' && OMP_NUM_THREADS=1 " + launcher + "'" + lmp + "' -in '" + script +
                          "' -log '" + log + "' -screen none > /dev/null 2>&1";
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
