#include "hgridlab/io/lammps_export.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/provenance.hpp"
#include "hgridlab/io/atomic_file.hpp"
#include "hgridlab/io/peer_settings.hpp"

namespace hgrid {
namespace {

void check(const Packing& p) {
  if (p.d != 2 && p.d != 3) throw InputError("d", "must be 2 or 3");
  if (p.size() == 0) throw InputError("radii", "empty packing: nothing to export");
  if (p.positions.size() != p.size() * static_cast<std::size_t>(p.d))
    throw InputError("positions", "expected N x d values");
  for (int a = 0; a < p.d; ++a)
    if (!(p.box[a] > 0) || !std::isfinite(p.box[a])) throw InputError("box", "side lengths must be finite and > 0");
}

double max_radius(const Packing& p) { return *std::max_element(p.radii.begin(), p.radii.end()); }
double min_radius(const Packing& p) { return *std::min_element(p.radii.begin(), p.radii.end()); }

}  // namespace

std::vector<double> geometric_collections(const Packing& p, int k, double smallest) {
  check(p);
  if (k < 1 || k > 64) throw InputError("collections", "number of size classes must be in [1, 64]");
  const double dmax = 2 * max_radius(p);
  if (!(smallest > 0) || !std::isfinite(smallest)) throw InputError("collections", "smallest class must be > 0");
  smallest = std::min(smallest, dmax);
  std::vector<double> c;
  for (int i = 0; i < k; ++i)
    c.push_back(k == 1 ? dmax : smallest * std::pow(dmax / smallest, static_cast<double>(i) / (k - 1)));
  c.back() = dmax;
  c.erase(std::unique(c.begin(), c.end()), c.end());  // smallest == dmax collapses to one class
  return c;
}

std::string lammps_collection_interval(const std::vector<double>& collections) {
  std::string line = "neigh_modify collection/interval " + std::to_string(collections.size());
  for (double v : collections) {  // piece by piece: GCC 12 warns (-Wrestrict) on " " + string
    line += ' ';
    line += shortest_number(v);
  }
  return line;
}

std::string lammps_data(const Packing& p) {
  check(p);
  const bool walls = p.boundary == Boundary::walls;
  std::string out = "LAMMPS data file (atom_style sphere) written by hgridlab " + std::string(version()) + " " + git_hash() + "\n\n";
  out += std::to_string(p.size()) + " atoms\n1 atom types\n\n";
  const char* ax[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    double lo = 0, hi = a < p.d ? p.box[a] : 0;
    if (a >= p.d) lo = -0.5, hi = 0.5;                 // 2D: thin z box around z = 0
    else if (walls) hi = p.box[a] * (1 + 1e-9);        // centres may sit on the top wall
    out += format_number(lo) + " " + format_number(hi) + " " + ax[a] + "lo " + ax[a] + "hi\n";
  }
  if (p.tilted())  // a triclinic box (grid/tilted_box.hpp: LAMMPS's own convention)
    out += format_number(p.tilt[0]) + " " + format_number(p.tilt[1]) + " " + format_number(p.tilt[2]) + " xy xz yz\n";
  out += "\nAtoms # sphere\n\n";
  std::string line;
  for (std::size_t i = 0; i < p.size(); ++i) {
    line = std::to_string(i + 1) + " 1 " + format_number(2 * p.radii[i]) + " 1";
    for (int a = 0; a < 3; ++a) {  // appended piece by piece: GCC 12 warns (-Wrestrict) on " " + string
      line += ' ';
      line += a < p.d ? format_number(p.positions[i * p.d + a]) : std::string("0");
    }
    out += line + "\n";
  }
  return out;
}

std::string lammps_input(const Packing& p, const LammpsScript& s) {
  check(p);
  if (s.builds < 1) throw InputError("builds", "must be >= 1");
  std::ostringstream o;
  o << "# hgridlab (" << provenance_line() << "): LAMMPS neighbour-list builds on an exported packing\n"
    << "# n = " << p.size() << ", d = " << p.d << ", " << to_string(p.boundary) << ", neighbor " << to_string(s.neighbor)
    << "\n# Per-pair cutoff r_i + r_j (granular size list), zero skin, rebuilt every step;\n"
    << "# no integrator: the particles never move. Read 'Neigh' time / 'Neighbor list builds'\n"
    << "# and 'Total # of neighbors' (each pair once) from the log.\n"
    << "units lj\natom_style sphere\ndimension " << p.d << "\n";
  const char* b = p.boundary == Boundary::periodic ? "p" : "f";
  o << "boundary " << b << " " << b << " " << (p.d == 2 ? "p" : b) << "\n"
    << "newton on\ncomm_modify vel yes\n"
    << "read_data " << s.data_file << "\n"
    << "pair_style gran/hooke 1.0 NULL 0.0 NULL 0.0 0\npair_coeff * *\n";
  if (s.neighbor == LammpsNeighbor::multi) {
    std::vector<double> c = s.collections.empty() ? geometric_collections(p, 4, 2 * min_radius(p)) : s.collections;
    const double dmax = 2 * max_radius(p);
    for (std::size_t i = 0; i < c.size(); ++i) {
      if (!(c[i] > 0) || !std::isfinite(c[i]) || (i > 0 && !(c[i] > c[i - 1])))
        throw InputError("collections", "class bounds must be finite, > 0 and increasing");
    }
    if (c.back() < dmax) throw InputError("collections", "the last class bound must be >= the largest diameter " + format_number(dmax));
    o << "neighbor 0.0 multi\n" << lammps_collection_interval(c) << "\ncomm_modify mode multi\n";
  } else {
    o << "neighbor 0.0 bin\n";
  }
  o << "neigh_modify every 1 delay 0 check no\n"
    << "thermo " << s.builds << "\ntimestep 0.0\n"
    << "run " << s.builds << "\n";
  return o.str();
}

void export_lammps(const std::string& dir, const Packing& p, const LammpsScript& s) {
  if (dir.empty()) throw InputError("lammps", "empty output directory");
  LammpsScript multi = s, bin = s;
  multi.neighbor = LammpsNeighbor::multi;
  bin.neighbor = LammpsNeighbor::bin;
  const std::string in_multi = lammps_input(p, multi), in_bin = lammps_input(p, bin);  // validate before writing
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError("lammps", "cannot create directory " + dir + ": " + ec.message());
  write_text_atomically(dir + "/" + s.data_file, lammps_data(p));
  write_text_atomically(dir + "/in.multi.lmp", in_multi);
  write_text_atomically(dir + "/in.bin.lmp", in_bin);
}

}  // namespace hgrid
