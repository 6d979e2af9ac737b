#include "hgridlab/io/viewer_files.hpp"

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/atomic_file.hpp"
#include "hgridlab/io/peer_settings.hpp"

namespace hgrid {
namespace {

void check(const Packing& p, const GridPlacement& g) {
  if (g.level.size() != p.size() || g.cell.size() != p.size())
    throw InputError("placement", "one level and one cell per particle expected");
}

/// The coordinate of axis a of particle i (0 beyond d).
double coord(const Packing& p, std::size_t i, int a) { return a < p.d ? p.positions[i * p.d + a] : 0.0; }

void append_number(std::string& out, double v) {
  out += ' ';
  out += shortest_number(v);
}

}  // namespace

std::string extended_xyz(const Packing& p, const GridPlacement& g) {
  check(p, g);
  const char* pbc = p.boundary == Boundary::periodic ? "T" : "F";
  std::string out = std::to_string(p.size()) + "\nLattice=\"";
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      if (a + b > 0) out += ' ';
      // Lattice vector a, component b: a = (lx, 0, 0), b = (xy, ly, 0), c = (xz, yz, lz).
      const double tilt = a == 1 && b == 0 ? p.tilt[0] : a == 2 && b == 0 ? p.tilt[1] : a == 2 && b == 1 ? p.tilt[2] : 0.0;
      out += shortest_number(a != b ? tilt : a < p.d ? p.box[a] : 1.0);
    }
  out += "\" Origin=\"0 0 0\" pbc=\"" + std::string(pbc) + " " + pbc + " " + (p.d == 3 ? pbc : "F") +
         "\" Properties=species:S:1:pos:R:3:radius:R:1:level:I:1:cell:I:1\n";
  for (std::size_t i = 0; i < p.size(); ++i) {
    out += 'P';
    for (int a = 0; a < 3; ++a) append_number(out, coord(p, i, a));
    append_number(out, p.radii[i]);
    out += ' ';
    out += std::to_string(g.level[i]);
    out += ' ';
    out += std::to_string(g.cell[i]);
    out += '\n';
  }
  return out;
}

std::string legacy_vtk(const Packing& p, const GridPlacement& g) {
  check(p, g);
  const std::string n = std::to_string(p.size());
  std::string out = "# vtk DataFile Version 3.0\nhgridlab particles: radius, level of insertion, cell\nASCII\n"
                    "DATASET POLYDATA\nPOINTS " + n + " double\n";
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      if (a > 0) out += ' ';
      out += shortest_number(coord(p, i, a));
    }
    out += '\n';
  }
  out += "VERTICES " + n + " " + std::to_string(2 * p.size()) + "\n";
  for (std::size_t i = 0; i < p.size(); ++i) out += "1 " + std::to_string(i) + "\n";
  out += "POINT_DATA " + n + "\nSCALARS radius double 1\nLOOKUP_TABLE default\n";
  for (double r : p.radii) out += shortest_number(r) + "\n";
  out += "SCALARS level int 1\nLOOKUP_TABLE default\n";
  for (int h : g.level) out += std::to_string(h) + "\n";
  out += "SCALARS cell double 1\nLOOKUP_TABLE default\n";
  for (std::uint64_t c : g.cell) out += std::to_string(c) + "\n";
  return out;
}

void write_extended_xyz(const std::string& path, const Packing& p, const GridPlacement& g) {
  write_text_atomically(path, extended_xyz(p, g), "xyz");
}

void write_legacy_vtk(const std::string& path, const Packing& p, const GridPlacement& g) {
  write_text_atomically(path, legacy_vtk(p, g), "vtk");
}

}  // namespace hgrid
