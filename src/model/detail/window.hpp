// The search window of a cell-aligned search, averaged over where the particle
// sits in its cell, and radial transforms used by the excluded-volume model
// (docs/MODEL.md section 8).
#pragma once
#include <vector>

namespace hgrid::detail {

/// Probability that a point at offset y (one axis) lies in the scanned cells,
/// for a scan of every cell meeting [x - c, x + c] with cells of side s and x
/// uniform in its cell: 1 for |y| <= c, falling linearly to 0 at c + s.
double window_1d(double y, double c, double s);

/// A_W(r): the integral of the 3D window prod_k window_1d(y_k) over the sphere
/// |y| = r (4 pi r^2 where the sphere lies inside the cube |y_k| <= c), at r_n = n dr,
/// n = 1 .. nmax (entries past the window's reach are 0).
std::vector<double> window_shell_areas(double c, double s, double dr, int nmax);

/// L_W(r): the integral of the 2D window window_1d(y_1) window_1d(y_2) over the
/// circle |y| = r (2 pi r where the circle lies inside the square |y_k| <= c),
/// at r_n = n dr, n = 0 .. nmax.
std::vector<double> window_circle_lengths(double c, double s, double dr, int nmax);

/// In place, x[n] <- sum_{m=1}^{N-1} x[m] sin(pi m n / N) for n = 1..N-1 (DST-I;
/// x[0] is ignored and set to 0). N = x.size() must be a power of two.
void sine_transform(std::vector<double>& x);

}  // namespace hgrid::detail
