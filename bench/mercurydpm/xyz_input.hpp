// The particles of an extended XYZ file as `hgrid export --xyz` writes it
// (io/viewer_files.cpp): N, a line with Lattice="..." (the box's edge
// vectors, row by row), then "P x y z r level cell" per particle. Read by
// the MercuryDPM drivers of this folder; a bad file exits 2 naming it.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace hgridlab_mercurydpm {

struct XyzInput {
  int d = 3;
  double L[3] = {0, 0, 0};   // the box's side lengths (the Lattice's diagonal)
  std::vector<double> x, r;  // x: N x d
};

[[noreturn]] inline void xyz_fail(const std::string& what) {
  std::fprintf(stderr, "%s\n", what.c_str());
  std::exit(2);
}

/// The first d coordinates of every particle (d = 2: z is dropped).
inline XyzInput read_xyz_input(const std::string& path, int d) {
  std::ifstream in(path);
  if (!in) xyz_fail("cannot read " + path);
  XyzInput p;
  p.d = d;
  std::string line;
  std::size_t n = 0;
  if (!std::getline(in, line) || !(std::istringstream(line) >> n) || n == 0) xyz_fail(path + ": no particle count");
  std::getline(in, line);
  const auto at = line.find("Lattice=\"");
  if (at == std::string::npos) xyz_fail(path + ": no Lattice");
  double l[9];
  std::istringstream lat(line.substr(at + 9));
  for (double& v : l)
    if (!(lat >> v)) xyz_fail(path + ": bad Lattice");
  for (int a = 0; a < d; ++a) p.L[a] = l[4 * a];
  p.x.resize(n * d);
  p.r.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::getline(in, line)) xyz_fail(path + ": fewer particles than its count");
    std::istringstream row(line);
    std::string species;
    double x[3];
    if (!(row >> species >> x[0] >> x[1] >> x[2] >> p.r[i])) xyz_fail(path + ": bad particle line");
    for (int a = 0; a < d; ++a) p.x[i * d + a] = x[a];
  }
  return p;
}

}  // namespace hgridlab_mercurydpm
