// A tilted (triclinic) periodic box: LAMMPS's lattice (docs.lammps.org,
// "Howto triclinic"), edge vectors a = (lx, 0, 0), b = (xy, ly, 0),
// c = (xz, yz, lz), i.e. x = H s with H upper triangular and s the fractional
// coordinates; in 2D a = (lx, 0), b = (xy, ly). A Lees-Edwards box (an
// orthogonal box whose images across the y faces are shifted along x by an
// offset) is the same lattice with xy = the offset less a multiple of lx, |xy| <= lx/2.
// Its grid is grid/tilted.hpp.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/grid/geometry.hpp"

namespace hgrid {

/// How far past half an edge a tilt may lie and still be at LAMMPS's limit
/// (a box written at the limit reads back a few ulps beyond it).
inline constexpr double kTiltLimitRelTol = 1e-12;
/// How much the inflation c is raised over the computed largest singular
/// value, so that rounding (~1e-15) cannot make a mapped sphere smaller than
/// the ellipsoid it stands for (a larger sphere only adds candidates).
inline constexpr double kInflationRelMargin = 1e-9;
/// How much a reach is raised before the shifts around the rounding are
/// counted (TiltedBox::image_reach), so that rounding in the fractional
/// coordinates (~1e-15) cannot leave the nearest image one shift outside.
inline constexpr double kImageReachRelMargin = 1e-9;

/// The tilts a box of dimension d has: {xy} (2D) or {xy, xz, yz} (3D), as
/// files and reports list them.
inline std::vector<double> tilt_values(const std::array<double, 3>& tilt, int d) {
  return std::vector<double>(tilt.begin(), tilt.begin() + (d == 2 ? 1 : 3));
}

/// A periodic box with tilts (LAMMPS's triclinic box, origin at 0).
template <int D>
struct TiltedBox {
  static_assert(D == 2 || D == 3, "d = 2 or 3");
  Extent<D> length{};                 // lx, ly (, lz), all > 0
  std::array<double, 3> tilt{};       // xy, xz, yz (2D: xy only; the others must be 0)

  /// The orthogonal box (all tilts 0).
  static TiltedBox orthogonal(const Extent<D>& l) { return TiltedBox{l, {}}; }
  /// Lees-Edwards: the images across the y faces shifted by `offset` along x.
  static TiltedBox lees_edwards(const Extent<D>& l, double offset) {
    TiltedBox b{l, {}};
    b.tilt[0] = offset - l[0] * std::nearbyint(offset / l[0]);
    return b;
  }

  bool tilted() const { return tilt[0] != 0 || tilt[1] != 0 || tilt[2] != 0; }
  double volume() const {
    double v = 1;
    for (int k = 0; k < D; ++k) v *= length[k];
    return v;
  }

  /// Fractional coordinates of a displacement (or a position): H^-1 x.
  std::array<double, D> fractional(const std::array<double, D>& x) const {
    std::array<double, D> s{};
    if constexpr (D == 3) {
      s[2] = x[2] / length[2];
      s[1] = (x[1] - tilt[2] * s[2]) / length[1];
      s[0] = (x[0] - tilt[0] * s[1] - tilt[1] * s[2]) / length[0];
    } else {
      s[1] = x[1] / length[1];
      s[0] = (x[0] - tilt[0] * s[1]) / length[0];
    }
    return s;
  }
  /// Cartesian vector of integer (or fractional) lattice coordinates: H n.
  std::array<double, D> cartesian(const std::array<double, D>& n) const {
    std::array<double, D> x{};
    if constexpr (D == 3) {
      x[0] = length[0] * n[0] + tilt[0] * n[1] + tilt[1] * n[2];
      x[1] = length[1] * n[1] + tilt[2] * n[2];
      x[2] = length[2] * n[2];
    } else {
      x[0] = length[0] * n[0] + tilt[0] * n[1];
      x[1] = length[1] * n[1];
    }
    return x;
  }
  /// Perpendicular width of the box across face k (the distance between the
  /// two lattice planes s_k = 0 and s_k = 1): 1 / |row k of H^-1|.
  double width(int k) const {
    std::array<double, D> row{};  // row k of H^-1, from H^-1 applied to the unit vectors
    for (int a = 0; a < D; ++a) {
      std::array<double, D> e{};
      e[a] = 1;
      row[a] = fractional(e)[k];
    }
    double n2 = 0;
    for (const double v : row) n2 += v * v;
    return 1 / std::sqrt(n2);
  }
  double min_width() const {
    double w = width(0);
    for (int k = 1; k < D; ++k) w = std::min(w, width(k));
    return w;
  }

  /// The mapped position A x = diag(l) H^-1 x, wrapped into the orthogonal box.
  std::array<double, D> mapped(const std::array<double, D>& x) const {
    std::array<double, D> s = fractional(x), m{};
    for (int k = 0; k < D; ++k) m[k] = detail::wrap(length[k] * (s[k] - std::floor(s[k])), length[k]);
    return m;
  }

  /// c: the largest singular value of A, the most a length grows by the map
  /// (exactly 1 at zero tilt; otherwise raised by kInflationRelMargin).
  double inflation() const {
    if (!tilted()) return 1.0;
    // A's columns are A e_a; the largest eigenvalue of A^T A by Jacobi rotations.
    double M[3][3] = {};
    std::array<std::array<double, D>, D> col{};
    for (int a = 0; a < D; ++a) {
      std::array<double, D> e{};
      e[a] = 1;
      const std::array<double, D> s = fractional(e);
      for (int k = 0; k < D; ++k) col[a][k] = length[k] * s[k];
    }
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b)
        for (int k = 0; k < D; ++k) M[a][b] += col[a][k] * col[b][k];
    for (int sweep = 0; sweep < 64; ++sweep) {
      double off = 0;
      for (int p = 0; p < D; ++p)
        for (int q = p + 1; q < D; ++q) off += M[p][q] * M[p][q];
      if (off < 1e-30) break;
      for (int p = 0; p < D; ++p)
        for (int q = p + 1; q < D; ++q) {
          if (M[p][q] == 0) continue;
          const double theta = (M[q][q] - M[p][p]) / (2 * M[p][q]);
          const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
          const double cs = 1 / std::sqrt(t * t + 1), sn = t * cs;
          for (int k = 0; k < D; ++k) {  // M <- M J, then J^T M
            const double mp = M[k][p], mq = M[k][q];
            M[k][p] = cs * mp - sn * mq;
            M[k][q] = sn * mp + cs * mq;
          }
          for (int k = 0; k < D; ++k) {
            const double mp = M[p][k], mq = M[q][k];
            M[p][k] = cs * mp - sn * mq;
            M[q][k] = sn * mp + cs * mq;
          }
        }
    }
    double lmax = 0;
    for (int k = 0; k < D; ++k) lmax = std::max(lmax, M[k][k]);
    return std::sqrt(lmax) * (1 + kInflationRelMargin);
  }

  /// LAMMPS's limit on a tilt: |xy| <= lx/2, |xz| <= lx/2, |yz| <= ly/2
  /// (a tilt beyond it is the same lattice as one within, which LAMMPS
  /// writes instead: its box flips). "" within, else what is beyond.
  std::string beyond_limit() const {
    static const char* const tname[3] = {"xy", "xz", "yz"};
    static const char* const lname[3] = {"lx", "lx", "ly"};
    for (int k = 0; k < (D == 2 ? 1 : 3); ++k) {
      const double l = length[k == 2 ? 1 : 0];
      if (std::abs(tilt[k]) > 0.5 * l * (1 + kTiltLimitRelTol))
        return std::string("tilt ") + tname[k] + " = " + format_number(tilt[k]) + " is beyond LAMMPS's limit |" +
               tname[k] + "| <= " + lname[k] + "/2 = " + format_number(0.5 * l);
    }
    return "";
  }

  /// How many lattice shifts either side of the fractional rounding
  /// (detail::nearest_shift) the nearest image of a displacement shorter
  /// than `reach` can lie, per axis k: the rounding leaves fractional
  /// coordinate k within 1/2 of 0 and the image's lies within reach /
  /// width(k) of it, so the two shifts differ by less than reach / width(k)
  /// + 1/2. 0 on every axis when reach is below half the narrowest width
  /// (the rounding alone finds the image); 1 up to one and a half widths.
  std::array<int, D> image_reach(double reach) const {
    std::array<int, D> m{};
    for (int k = 0; k < D; ++k)
      m[k] = std::max(0, static_cast<int>(std::ceil(reach * (1 + kImageReachRelMargin) / width(k) + 0.5)) - 1);
    return m;
  }

  /// Throws InputError unless the lengths are finite and > 0, the tilts
  /// finite (2D: xz = yz = 0) and within LAMMPS's limit. A box of any
  /// width is searched: where pairs reach past half its narrowest width,
  /// further images are tried (image_reach).
  void check() const {
    static const char* const name[3] = {"lx", "ly", "lz"};
    for (int k = 0; k < D; ++k)
      if (!(std::isfinite(length[k]) && length[k] > 0))
        throw InputError("box", std::string(name[k]) + " must be finite and > 0");
    static const char* const tname[3] = {"xy", "xz", "yz"};
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(tilt[k])) throw InputError("box", std::string(tname[k]) + " tilt must be finite");
      if (D == 2 && k > 0 && tilt[k] != 0) throw InputError("box", std::string(tname[k]) + " tilt must be 0 in 2D");
    }
    if (const std::string e = beyond_limit(); !e.empty()) throw InputError("box", e);
  }
};

namespace detail {
/// The lattice's displacement from a to b nearest in fractional terms:
/// (b - a) + H n with n = -round(H^-1 (b - a)), and its squared length.
template <int D>
inline double tilted_dist2(const TiltedBox<D>& box, const std::array<double, D>& a, const std::array<double, D>& b,
                           const std::array<double, D>& shift) {
  std::array<double, D> dx{};
  for (int k = 0; k < D; ++k) dx[k] = b[k] - a[k];
  const std::array<double, D> v = box.cartesian(shift);
  double s = 0;
  for (int k = 0; k < D; ++k) {
    const double e = dx[k] + v[k];
    s += e * e;
  }
  return s;
}
template <int D>
inline std::array<double, D> nearest_shift(const TiltedBox<D>& box, const std::array<double, D>& a,
                                           const std::array<double, D>& b) {
  std::array<double, D> dx{};
  for (int k = 0; k < D; ++k) dx[k] = b[k] - a[k];
  std::array<double, D> n = box.fractional(dx);
  for (auto& v : n) v = -std::nearbyint(v);
  return n;
}

/// The nearest lattice image of b seen from a among the shifts n0 + o,
/// |o_k| <= m_k, around the fractional rounding n0 = nearest_shift(a, b)
/// (m from TiltedBox::image_reach): its squared length (tilted_dist2), and
/// its shift in `shift`. The rounding's image unless another is strictly
/// nearer; with m = 0 the rounding's alone, as when the box is wide.
template <int D>
inline double nearest_image(const TiltedBox<D>& box, const std::array<double, D>& a, const std::array<double, D>& b,
                            const std::array<int, D>& m, std::array<double, D>& shift) {
  const std::array<double, D> n0 = nearest_shift<D>(box, a, b);
  shift = n0;
  double best = tilted_dist2<D>(box, a, b, n0);
  bool wide = true;
  for (int k = 0; k < D; ++k) wide = wide && m[k] == 0;
  if (wide) return best;
  std::array<int, D> o{};
  for (int k = 0; k < D; ++k) o[k] = -m[k];
  while (true) {
    std::array<double, D> n = n0;
    for (int k = 0; k < D; ++k) n[k] += o[k];
    if (const double s = tilted_dist2<D>(box, a, b, n); s < best) {
      best = s;
      shift = n;
    }
    int k = 0;  // the next offset, odometer-wise
    for (; k < D; ++k) {
      if (o[k] < m[k]) {
        ++o[k];
        break;
      }
      o[k] = -m[k];
    }
    if (k == D) break;
  }
  return best;
}
}  // namespace detail

}  // namespace hgrid
