// One axis of a box with walls: what a scan of cells covers, averaged over
// the scanning particle's position (docs/MODEL.md section 8).
#pragma once
#include <vector>

namespace hgrid::detail {

struct AxisScan {
  double cells = 0;                // expected number of cells scanned
  double p_below = 0, p_above = 0; // own-level: probability the cell below / above exists
  std::vector<double> fraction;    // per searched radius b: expected share of [b, A - b] inside the scan
};

/// A particle of radius a, its centre uniform in [a, A - a], on a level of
/// cells of side s (n = ceil(A / s), cell 0 at the wall). own: the cells
/// i-1..i+1 around its cell i; otherwise every cell from (x - beta) to (x + beta).
/// Scans are clipped to [0, n-1].
AxisScan scan_axis(double A, double a, double s, bool own, double beta, const std::vector<double>& b);

}  // namespace hgrid::detail
