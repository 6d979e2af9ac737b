// Files for viewers (io/viewer_files, packing/grid_placement): each
// particle's level of insertion and cell, hand-worked; `hgrid export --xyz
// --vtk` writes both or nothing.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "cli_support.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/io/viewer_files.hpp"
#include "hgridlab/packing/grid_placement.hpp"

namespace hgrid::test {
namespace {

/// A 4 x 4 walled box, sizes {1, 4}: level 1 has 4 x 4 cells of side 1
/// (key = 4 cx + cy), level 2 one cell.
Packing small_2d() {
  Packing p;
  p.d = 2;
  p.boundary = Boundary::walls;
  p.box = {4, 4, 0};
  p.positions = {0.5, 0.5, 3.5, 1.5, 2, 2};
  p.radii = {0.25, 0.5, 1.5};
  return p;
}

TEST(ViewerFiles, PlacementHandWorked) {
  const GridPlacement g = place_in_grid(small_2d(), GridParams{{1, 4}, Search::top_down});
  EXPECT_EQ(g.sizes, (std::vector<double>{1, 4}));
  EXPECT_EQ(g.level, (std::vector<int>{1, 1, 2}));  // 2 r = 0.5 and 1 <= 1 < 3
  EXPECT_EQ(g.cell, (std::vector<std::uint64_t>{0, 13, 0}));
  // Periodic: centres wrapped first; 3 cells of side 4/3 per axis for size 1.2.
  Packing q = small_2d();
  q.boundary = Boundary::periodic;
  q.positions = {-0.5, 0.5, 3.5, 1.5, 2, 2};
  const GridPlacement h = place_in_grid(q, GridParams{{1.2, 4}, Search::top_down});
  EXPECT_DOUBLE_EQ(h.sizes[0], 4.0 / 3);
  EXPECT_EQ(h.cell[0], 2u * 3 + 0);  // x = 3.5 -> cx 2, y = 0.5 -> cy 0
  EXPECT_THROW(place_in_grid(small_2d(), GridParams{{1, 2}, Search::top_down}), InputError);  // 2 < largest diameter
}

TEST(ViewerFiles, ExtendedXyzAndLegacyVtkText) {
  const Packing p = small_2d();
  const GridPlacement g = place_in_grid(p, GridParams{{1, 4}, Search::top_down});
  EXPECT_EQ(extended_xyz(p, g),
            "3\nLattice=\"4 0 0 0 4 0 0 0 1\" Origin=\"0 0 0\" pbc=\"F F F\" "
            "Properties=species:S:1:pos:R:3:radius:R:1:level:I:1:cell:I:1\n"
            "P 0.5 0.5 0 0.25 1 0\nP 3.5 1.5 0 0.5 1 13\nP 2 2 0 1.5 2 0\n");
  EXPECT_EQ(legacy_vtk(p, g),
            "# vtk DataFile Version 3.0\nhgridlab particles: radius, level of insertion, cell\nASCII\n"
            "DATASET POLYDATA\nPOINTS 3 double\n0.5 0.5 0\n3.5 1.5 0\n2 2 0\nVERTICES 3 6\n1 0\n1 1\n1 2\n"
            "POINT_DATA 3\nSCALARS radius double 1\nLOOKUP_TABLE default\n0.25\n0.5\n1.5\n"
            "SCALARS level int 1\nLOOKUP_TABLE default\n1\n1\n2\n"
            "SCALARS cell double 1\nLOOKUP_TABLE default\n0\n13\n0\n");
  GridPlacement short_g = g;
  short_g.level.pop_back();
  EXPECT_THROW(extended_xyz(p, short_g), InputError);
}

using ViewerCli = TempDir;

TEST_F(ViewerCli, ExportWritesBothOrNothing) {
  std::ofstream(path("p.csv")) << "# box 4 4\n# boundary walls\nx,y,r\n0.5,0.5,0.25\n3.5,1.5,0.5\n2,2,1.5\n";
  Result r = hgrid_run("export " + path("p.csv") + " --xyz " + path("p.xyz") + " --vtk " + path("p.vtk") +
                       " --sizes 1,4");
  ASSERT_EQ(r.status, 0) << r.err;
  std::stringstream xyz;
  xyz << std::ifstream(path("p.xyz")).rdbuf();
  EXPECT_NE(xyz.str().find("P 3.5 1.5 0 0.5 1 13\n"), std::string::npos) << xyz.str();
  EXPECT_TRUE(fs::exists(path("p.vtk")));
  // Recommended sizes by default: every particle in some level.
  r = hgrid_run("export " + path("p.csv") + " --xyz " + path("q.xyz"), "HGRID_CALIBRATION=/nonexistent");
  EXPECT_EQ(r.status, 0) << r.err;
  // Bad sizes: exit 2, one line naming them, no file.
  r = hgrid_run("export " + path("p.csv") + " --xyz " + path("bad.xyz") + " --vtk " + path("bad.vtk") + " --sizes 1,2");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("sizes"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("bad.xyz")));
  EXPECT_FALSE(fs::exists(path("bad.vtk")));
  r = hgrid_run("export " + path("p.csv"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--xyz"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace hgrid::test
