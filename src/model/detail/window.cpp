// Search windows and the sine transform; see window.hpp.
#include "hgridlab/model/detail/window.hpp"

#include <gsl/gsl_fft_real.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace hgrid::detail {

namespace {
// Directions on the unit sphere (a Fibonacci lattice): the window is
// averaged over them. 400 directions integrate A_W to ~1e-4 relative.
constexpr int kDirections = 400;

const std::vector<std::array<double, 3>>& directions() {
  static const std::vector<std::array<double, 3>> dirs = [] {
    std::vector<std::array<double, 3>> d(kDirections);
    const double golden = std::numbers::pi * (1.0 + std::sqrt(5.0));
    for (int i = 0; i < kDirections; ++i) {
      const double u = (i + 0.5) / kDirections, ph = std::acos(1.0 - 2.0 * u), th = golden * (i + 0.5);
      d[i] = {std::fabs(std::cos(th) * std::sin(ph)), std::fabs(std::sin(th) * std::sin(ph)), std::fabs(std::cos(ph))};
    }
    return d;
  }();
  return dirs;
}
}  // namespace

double window_1d(double y, double c, double s) {
  return std::clamp((c + s - std::fabs(y)) / s, 0.0, 1.0);
}

namespace {
// The window averaged over the sphere of radius r (1 inside the flat part).
double shell_mean(double r, double c, double s) {
  if (r <= c) return 1.0;
  double w = 0.0;
  for (const auto& u : directions()) w += window_1d(r * u[0], c, s) * window_1d(r * u[1], c, s) * window_1d(r * u[2], c, s);
  return w / kDirections;
}

// The 2D window averaged over the circle of radius r (by symmetry, over a
// quarter: kAngles midpoint angles in (0, pi/2)).
constexpr int kAngles = 400;
double circle_mean(double r, double c, double s) {
  if (r <= c) return 1.0;
  double w = 0.0;
  for (int i = 0; i < kAngles; ++i) {
    const double t = (i + 0.5) * (0.5 * std::numbers::pi / kAngles);
    w += window_1d(r * std::cos(t), c, s) * window_1d(r * std::sin(t), c, s);
  }
  return w / kAngles;
}

// The window integrated over spheres (d = 3) or circles (d = 2) of radius
// r_n = n dr: surface(r) times the mean over directions. That mean is smooth
// between its kinks (r = c, c sqrt 2, c sqrt 3, ...): computed on at most
// kShellNodes nodes across the window's reach and interpolated linearly
// (relative error ~1e-6 against computing it at every r).
constexpr int kShellNodes = 1024;
std::vector<double> over_spheres(int d, double c, double s, double dr, int nmax) {
  std::vector<double> a(static_cast<std::size_t>(nmax) + 1, 0.0);
  const double reach = std::sqrt(double(d)) * (c + s);
  const double h = std::max(dr, reach / kShellNodes);
  std::vector<double> node(static_cast<std::size_t>(std::ceil(reach / h)) + 2);
  for (std::size_t i = 0; i < node.size(); ++i) node[i] = d == 3 ? shell_mean(i * h, c, s) : circle_mean(i * h, c, s);
  for (int n = 1; n <= nmax; ++n) {
    const double r = n * dr;
    if (r >= reach) break;
    const double t = r / h;
    const auto i = static_cast<std::size_t>(t);
    const double w = r <= c ? 1.0 : node[i] + (t - i) * (node[i + 1] - node[i]);
    a[n] = (d == 3 ? 4.0 * std::numbers::pi * r * r : 2.0 * std::numbers::pi * r) * w;
  }
  return a;
}
}  // namespace

std::vector<double> window_shell_areas(double c, double s, double dr, int nmax) { return over_spheres(3, c, s, dr, nmax); }

std::vector<double> window_circle_lengths(double c, double s, double dr, int nmax) {
  return over_spheres(2, c, s, dr, nmax);
}

void sine_transform(std::vector<double>& x) {
  const std::size_t N = x.size();
  if (N < 2 || (N & (N - 1)) != 0) throw std::invalid_argument("sine_transform: size must be a power of two");
  // Odd extension of length 2N; its FFT is -2i times the DST.
  std::vector<double> y(2 * N, 0.0);
  for (std::size_t m = 1; m < N; ++m) {
    y[m] = x[m];
    y[2 * N - m] = -x[m];
  }
  gsl_fft_real_radix2_transform(y.data(), 1, 2 * N);
  x[0] = 0.0;
  for (std::size_t n = 1; n < N; ++n) x[n] = -0.5 * y[2 * N - n];  // halfcomplex: Im(Y_n) at [2N - n]
}

}  // namespace hgrid::detail
