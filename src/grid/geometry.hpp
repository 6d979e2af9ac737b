// Spheres, boxes and boundaries: the vocabulary shared by every search structure.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <string_view>

#include "hgridlab/base/error.hpp"

namespace hgrid {

/// A d-sphere (a disk for D = 2): centre and radius.
template <int D>
struct Sphere {
  std::array<double, D> x;
  double r;
};

enum class Boundary { walls, periodic };

inline const char* to_string(Boundary b) { return b == Boundary::walls ? "walls" : "periodic"; }

/// "periodic" or "walls"; anything else throws InputError naming `field`.
inline Boundary parse_boundary(std::string_view s, const std::string& field = "boundary") {
  if (s == "periodic") return Boundary::periodic;
  if (s == "walls") return Boundary::walls;
  throw InputError(field, "must be 'periodic' or 'walls' (got '" + std::string(s) + "')");
}

/// Volume of the unit d-ball: pi (d = 2), 4 pi / 3 (d = 3).
inline double unit_ball_volume(int d) { return d == 2 ? M_PI : 4.0 * M_PI / 3.0; }

/// Volume of a d-sphere of radius r.
inline double ball_volume(int d, double r) { return unit_ball_volume(d) * (d == 2 ? r * r : r * r * r); }

/// Axis-aligned box [0, side_k) per axis. With walls, centres must lie in
/// [0, side_k]; with periodic boundaries they are wrapped into [0, side_k).
template <int D>
using Extent = std::array<double, D>;

/// Cells per axis of a level of cell size s in a box side A: with periodic
/// boundaries an integer number of cells at least s wide tiles the side
/// (fitted; at least one), with walls cells of side s cover it.
inline double cells_per_axis(double A, double s, Boundary b) {
  const double ratio = A / s;
  return std::max(1.0, b == Boundary::periodic ? std::floor(ratio) : std::ceil(ratio));
}

namespace detail {

/// Wraps a coordinate into [0, a) (periodic boundary).
inline double wrap(double x, double a) {
  if (x >= 0 && x < a) return x;  // the usual case, exact, and no division
  x -= a * std::floor(x / a);
  return x >= a ? 0.0 : x;  // a tiny negative x can round up to a
}

/// Minimum-image displacement along one periodic axis, for |dx| < a.
inline double min_image(double dx, double a) {
  if (dx > 0.5 * a) return dx - a;
  if (dx < -0.5 * a) return dx + a;
  return dx;
}

/// Squared centre distance; the axes whose bit is set in Periodic use the
/// minimum image (a contact list's boundaries per axis).
template <int D, unsigned Periodic>
inline double dist2_axes(const std::array<double, D>& a, const std::array<double, D>& b, const Extent<D>& box) {
  double s = 0.0;
  for (int k = 0; k < D; ++k) {
    double dx = b[k] - a[k];
    if (Periodic >> k & 1u) dx = min_image(dx, box[k]);
    s += dx * dx;
  }
  return s;
}

/// The narrow-phase test: strictly overlapping bounding spheres; Periodic
/// as dist2_axes.
template <int D, unsigned Periodic>
inline bool overlap_axes(const Sphere<D>& p, const Sphere<D>& q, const Extent<D>& box) {
  const double rs = p.r + q.r;
  return dist2_axes<D, Periodic>(p.x, q.x, box) < rs * rs;
}

/// The axes' periodic bits of a boundary for every axis.
template <int D, Boundary B>
inline constexpr unsigned kPeriodicAxes = B == Boundary::periodic ? (1u << D) - 1 : 0u;

/// Squared centre distance; periodic axes use the minimum image.
template <int D, Boundary B>
inline double dist2(const std::array<double, D>& a, const std::array<double, D>& b,
                    const Extent<D>& box) {
  return dist2_axes<D, kPeriodicAxes<D, B>>(a, b, box);
}

/// The narrow-phase test: strictly overlapping bounding spheres.
template <int D, Boundary B>
inline bool overlap(const Sphere<D>& p, const Sphere<D>& q, const Extent<D>& box) {
  return overlap_axes<D, kPeriodicAxes<D, B>>(p, q, box);
}

}  // namespace detail
}  // namespace hgrid
