// One axis of a box with walls: what a scan of cells covers, averaged over
// the scanning particle's position (docs/MODEL.md section 8).
#pragma once
#include <vector>

namespace hgrid::detail {

/// The density of one size class across an axis [0, A] with walls at both
/// ends: zero within `radius` of a wall, else 1 + h(z) + h(A - z) (h(z): the
/// class's wall correlation at distance z from a wall, tabulated every dz from
/// z = 0; 0 beyond the table; an empty table is a uniform density).
struct WallProfile {
  double radius = 0;
  double dz = 1;
  std::vector<double> h;
  /// Where h jumps from -1 to its contact value (0: no jump inside the table);
  /// h is interpolated from nodes on one side of it only.
  double contact = 0;
};

struct AxisScan {
  double cells = 0;                // expected number of cells scanned
  double p_below = 0, p_above = 0; // own-level: probability the cell below / above exists
  std::vector<double> fraction;    // per searched class: expected share of its particles inside the scan
  std::vector<double> fraction_interior;  // the same, counting only scanning positions at least `layer` from both walls
};

/// A particle of the class `a` on a level of cells of side s (n = ceil(A / s),
/// cell 0 at the wall). own: the cells i-1..i+1 around its cell i; otherwise
/// every cell from (x - beta) to (x + beta). Scans are clipped to [0, n-1].
/// fraction_interior counts only scanning positions x in [layer, A - layer].
AxisScan scan_axis(double A, const WallProfile& a, double s, bool own, double beta, const std::vector<WallProfile>& b,
                   double layer = 0);

}  // namespace hgrid::detail
