// The same-level search stencil: the own cell plus HALF of the 3^d - 1
// neighbours, so that no pair of cells is visited twice (docs/MODEL.md section 1).
#pragma once
#include <array>
#include <cstdint>

#include "hgridlab/grid/detail/levels.hpp"

namespace hgrid::detail {

constexpr int pow3(int d) { return d == 0 ? 1 : 3 * pow3(d - 1); }

/// n_c = (3^d - 1) / 2: 4 in 2D, 13 in 3D.
template <int D>
inline constexpr int kHalfStencil = (pow3(D) - 1) / 2;

/// The offsets in {-1,0,1}^D whose first non-zero component is +1.
template <int D>
constexpr std::array<std::array<int, D>, kHalfStencil<D>> half_offsets() {
  std::array<std::array<int, D>, kHalfStencil<D>> out{};
  int m = 0;
  for (int code = 0; code < pow3(D); ++code) {
    std::array<int, D> o{};
    int c = code;
    for (int a = 0; a < D; ++a) {
      o[a] = c % 3 - 1;
      c /= 3;
    }
    int first = 0;
    for (int a = 0; a < D && first == 0; ++a) first = o[a];
    if (first > 0) out[m++] = o;
  }
  return out;
}

/// Calls f(coords) once for each distinct cell of the half stencil of cell c.
/// Walls: neighbours beyond the box do not exist and are skipped. Periodic:
/// indices wrap; on a level with fewer than 3 cells on some axis the +1 and -1
/// neighbours coincide, so there the direction of a neighbour along that axis
/// is the sign of the index difference instead of the offset. That relation is
/// still antisymmetric, so each pair of distinct cells is visited exactly once.
template <int D, Boundary B, class F>
inline void for_each_half_neighbour(const Level<D>& L, const std::array<std::int64_t, D>& c, F&& f) {
  if (B == Boundary::walls || !L.small_periodic) {
    static constexpr auto offsets = half_offsets<D>();
    for (const auto& o : offsets) {
      std::array<std::int64_t, D> nc;
      bool inside = true;
      for (int a = 0; a < D; ++a) {
        std::int64_t i = c[a] + o[a];
        if constexpr (B == Boundary::walls) {
          inside = inside && i >= 0 && i < L.n[a];
        } else {
          if (i < 0) i += L.n[a];
          if (i >= L.n[a]) i -= L.n[a];
        }
        nc[a] = i;
      }
      if (inside) f(nc);
    }
    return;
  }
  // General periodic path: per axis the distinct cells with their direction.
  std::array<std::array<std::int64_t, 3>, D> idx{};
  std::array<std::array<int, 3>, D> dir{};
  std::array<int, D> count{};
  for (int a = 0; a < D; ++a) {
    const std::int64_t n = L.n[a];
    if (n >= 3) {
      idx[a] = {(c[a] + n - 1) % n, c[a], (c[a] + 1) % n};
      dir[a] = {-1, 0, 1};
      count[a] = 3;
    } else if (n == 2) {
      idx[a] = {c[a], 1 - c[a], 0};
      dir[a] = {0, (1 - c[a]) > c[a] ? 1 : -1, 0};
      count[a] = 2;
    } else {
      idx[a] = {c[a], 0, 0};
      dir[a] = {0, 0, 0};
      count[a] = 1;
    }
  }
  int total = 1;
  for (int a = 0; a < D; ++a) total *= count[a];
  for (int code = 0; code < total; ++code) {
    std::array<std::int64_t, D> nc;
    int first = 0;
    int rest = code;
    for (int a = 0; a < D; ++a) {
      const int k = rest % count[a];
      rest /= count[a];
      nc[a] = idx[a][k];
      if (first == 0) first = dir[a][k];
    }
    if (first > 0) f(nc);
  }
}

}  // namespace hgrid::detail
