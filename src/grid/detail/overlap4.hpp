// The narrow-phase test of one sphere against four consecutive spheres of an
// array at once (AVX2), for the long candidate runs of dense cells (a linked
// cell's cells hold ~100 small spheres, and its same-level pass was three
// quarters of a DPM step).
//
// Each lane does the scalar test's IEEE operations in the scalar test's
// order (geometry.hpp: dx = q - p per axis, the minimum image where asked,
// s = ((0 + dx0^2) + dx1^2) [+ dx2^2], rs = r_p + r_q, s < rs^2), and the
// build has no contraction (-ffp-contract=off), so every lane's answer is
// the scalar test's, bit for bit. Without AVX2 the scalar test runs.
#pragma once
#include <array>
#include <bit>
#include <cstdint>
#include <utility>

#include "hgridlab/grid/geometry.hpp"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace hgrid::detail {

#if defined(__AVX2__)
inline constexpr bool kOverlap4 = true;

/// Bit t set if the spheres of lane t overlap: centres p[0..D), radii pr
/// against centres x[0..D), radii r; the scalar test's operations, lane by
/// lane (dx = x - p, rs = pr + r); the axes whose bit is set in Periodic
/// take the minimum image.
template <int D, unsigned Periodic>
inline unsigned overlap4_lanes_pq(const __m256d (&p)[D], __m256d pr, const __m256d (&x)[D], __m256d r,
                                  const Extent<D>& box) {
  __m256d s2 = _mm256_setzero_pd();
  for (int k = 0; k < D; ++k) {
    __m256d dx = _mm256_sub_pd(x[k], p[k]);
    if constexpr (Periodic != 0) {
      if (Periodic >> k & 1u) {  // min_image: dx - a above a/2, dx + a below -a/2
        const __m256d a = _mm256_set1_pd(box[k]), half = _mm256_set1_pd(0.5 * box[k]),
                      nhalf = _mm256_set1_pd(-0.5 * box[k]);
        const __m256d above = _mm256_cmp_pd(dx, half, _CMP_GT_OQ), below = _mm256_cmp_pd(dx, nhalf, _CMP_LT_OQ);
        dx = _mm256_blendv_pd(_mm256_blendv_pd(dx, _mm256_sub_pd(dx, a), above), _mm256_add_pd(dx, a), below);
      }
    }
    s2 = _mm256_add_pd(s2, _mm256_mul_pd(dx, dx));
  }
  const __m256d rs = _mm256_add_pd(pr, r);
  return static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(s2, _mm256_mul_pd(rs, rs), _CMP_LT_OQ)));
}

/// The same, one sphere p against the four lanes.
template <int D, unsigned Periodic>
inline unsigned overlap4_lanes_axes(const Sphere<D>& p, const __m256d (&x)[D], __m256d r, const Extent<D>& box) {
  __m256d pv[D];
  for (int k = 0; k < D; ++k) pv[k] = _mm256_set1_pd(p.x[k]);
  return overlap4_lanes_pq<D, Periodic>(pv, _mm256_set1_pd(p.r), x, r, box);
}

/// The same with one boundary for every axis.
template <int D, Boundary B>
inline unsigned overlap4_lanes(const Sphere<D>& p, const __m256d (&x)[D], __m256d r, const Extent<D>& box) {
  return overlap4_lanes_axes<D, kPeriodicAxes<D, B>>(p, x, r, box);
}

/// Four (x0, x1, x2, r) rows l0..l3 as coordinates: lane t of x[k] is
/// row t's x_k, of r its radius.
inline void transpose4(__m256d l0, __m256d l1, __m256d l2, __m256d l3, __m256d (&x)[3], __m256d& r) {
  const __m256d t0 = _mm256_unpacklo_pd(l0, l1), t1 = _mm256_unpackhi_pd(l0, l1);
  const __m256d t2 = _mm256_unpacklo_pd(l2, l3), t3 = _mm256_unpackhi_pd(l2, l3);
  x[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
  x[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
  x[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
  r = _mm256_permute2f128_pd(t1, t3, 0x31);
}

/// Bit t set if sphere p overlaps s[t], t = 0..3.
template <int D, Boundary B>
inline unsigned overlap4(const Sphere<D>& p, const Sphere<D>* s, const Extent<D>& box) {
  static_assert(D == 2 || D == 3);
  static_assert(sizeof(Sphere<D>) == (D + 1) * sizeof(double));
  const double* m = &s[0].x[0];
  __m256d x[D], r;
  if constexpr (D == 3) {  // four (x0, x1, x2, r) rows transposed
    transpose4(_mm256_loadu_pd(m), _mm256_loadu_pd(m + 4), _mm256_loadu_pd(m + 8), _mm256_loadu_pd(m + 12), x, r);
  } else {  // four (x0, x1, r) triples: a = [a0 a1 ar b0], b = [b1 br c0 c1], c = [cr d0 d1 dr]
    const __m256d a = _mm256_loadu_pd(m), b = _mm256_loadu_pd(m + 4), c = _mm256_loadu_pd(m + 8);
    const __m256d u = _mm256_blend_pd(_mm256_blend_pd(a, b, 0b0100), c, 0b0010);  // [a0 d0 c0 b0]
    const __m256d v = _mm256_blend_pd(_mm256_blend_pd(a, b, 0b1001), c, 0b0100);  // [b1 a1 d1 c1]
    const __m256d w = _mm256_blend_pd(_mm256_blend_pd(a, b, 0b0010), c, 0b1001);  // [cr br ar dr]
    x[0] = _mm256_permute4x64_pd(u, 0b01101100);  // lanes 0 3 2 1
    x[1] = _mm256_permute4x64_pd(v, 0b10110001);  // lanes 1 0 3 2
    r = _mm256_permute4x64_pd(w, 0b11000110);     // lanes 2 1 0 3
  }
  return overlap4_lanes<D, B>(p, x, r, box);
}

/// The same test against spheres t..t+3 of coordinate arrays a[0..D)
/// and radii a[D] (a gathered run, stored by coordinate): four loads
/// instead of four loads and eight shuffles (a pour's list build: -8 %).
template <int D, Boundary B, class Arrays>
inline unsigned overlap4_soa(const Sphere<D>& p, const Arrays& a, std::uint32_t t, const Extent<D>& box) {
  __m256d x[D];
  for (int k = 0; k < D; ++k) x[k] = _mm256_loadu_pd(a[k].data() + t);
  return overlap4_lanes<D, B>(p, x, _mm256_loadu_pd(a[D].data() + t), box);
}

/// Spheres s[idx[0..4)] by coordinate: lane t of x[k] is s[idx[t]].x[k],
/// of r its radius.
template <int D>
inline void load4_indexed(const Sphere<D>* s, const std::uint32_t* idx, __m256d (&x)[D], __m256d& r) {
  static_assert(D == 2 || D == 3);
  static_assert(sizeof(Sphere<D>) == (D + 1) * sizeof(double));
  if constexpr (D == 3) {  // four (x0, x1, x2, r) rows transposed
    transpose4(_mm256_loadu_pd(&s[idx[0]].x[0]), _mm256_loadu_pd(&s[idx[1]].x[0]), _mm256_loadu_pd(&s[idx[2]].x[0]),
               _mm256_loadu_pd(&s[idx[3]].x[0]), x, r);
  } else {  // four (x0, x1) pairs: [a0 a1 b0 b1], [c0 c1 d0 d1] -> lanes a b c d; radii one by one
    const __m256d ab = _mm256_set_m128d(_mm_loadu_pd(&s[idx[1]].x[0]), _mm_loadu_pd(&s[idx[0]].x[0]));
    const __m256d cd = _mm256_set_m128d(_mm_loadu_pd(&s[idx[3]].x[0]), _mm_loadu_pd(&s[idx[2]].x[0]));
    x[0] = _mm256_permute4x64_pd(_mm256_unpacklo_pd(ab, cd), 0b11011000);  // [a0 c0 b0 d0] -> [a0 b0 c0 d0]
    x[1] = _mm256_permute4x64_pd(_mm256_unpackhi_pd(ab, cd), 0b11011000);
    r = _mm256_setr_pd(s[idx[0]].r, s[idx[1]].r, s[idx[2]].r, s[idx[3]].r);
  }
}

/// Bit t set if s[first[t]] overlaps s[second[t]], t = 0..3: four pairs of
/// a list, each its own two spheres (dx = x_second - x_first); the axes whose
/// bit is set in Periodic take the minimum image.
template <int D, unsigned Periodic>
inline unsigned overlap4_pairs(const Sphere<D>* s, const std::uint32_t* first, const std::uint32_t* second,
                               const Extent<D>& box) {
  __m256d p[D], pr, x[D], r;
  load4_indexed<D>(s, first, p, pr);
  load4_indexed<D>(s, second, x, r);
  return overlap4_lanes_pq<D, Periodic>(p, pr, x, r, box);
}

/// For each 4-bit mask, the 32-bit lanes of its set bits, packed to the front.
inline constexpr auto kCompressLanes = [] {
  std::array<std::array<std::int32_t, 4>, 16> t{};
  for (unsigned m = 0; m < 16; ++m) {
    unsigned k = 0;
    for (unsigned b = 0; b < 4; ++b)
      if (m >> b & 1u) t[m][k++] = static_cast<std::int32_t>(b);
  }
  return t;
}();

/// Writes idx[t], t the set bits of a 4-bit mask, lowest first, to
/// out[0..popcount): one 16-byte store (the lanes past the count are
/// scratch, so out must have room for four), no branch on the mask.
/// Returns the count.
inline unsigned compress4(std::uint32_t* out, const std::uint32_t* idx, unsigned bits) {
  const __m128 v = _mm_castsi128_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(idx)));
  const __m128i lanes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(kCompressLanes[bits].data()));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm_castps_si128(_mm_permutevar_ps(v, lanes)));
  return static_cast<unsigned>(std::popcount(bits));
}

/// For each 4-bit mask, the 32-bit lanes of four pairs (p, q_0) ... (p, q_3)
/// that make its pairs, packed to the front.
inline constexpr auto kAppendLanes = [] {
  std::array<std::array<std::int32_t, 8>, 16> t{};
  for (unsigned m = 0; m < 16; ++m) {
    unsigned k = 0;
    for (unsigned b = 0; b < 4; ++b)
      if (m >> b & 1u) {
        t[m][2 * k] = static_cast<std::int32_t>(2 * b);
        t[m][2 * k + 1] = static_cast<std::int32_t>(2 * b + 1);
        ++k;
      }
    for (; k < 4; ++k) t[m][2 * k + 1] = 1;
  }
  return t;
}();

/// Writes the pairs (p, q + t), t the set bits of a 4-bit mask, lowest
/// first, to out[0..popcount): one 32-byte store of four pairs (those past
/// the count are scratch, so out must have room for four), no branch on
/// the mask. Returns the count.
inline unsigned append4(std::pair<std::uint32_t, std::uint32_t>* out, std::uint32_t p, std::uint32_t q,
                        unsigned bits) {
  static_assert(sizeof(std::pair<std::uint32_t, std::uint32_t>) == 8);
  const auto pi = static_cast<std::int32_t>(p), qi = static_cast<std::int32_t>(q);
  const __m256i pairs = _mm256_add_epi32(_mm256_setr_epi32(pi, qi, pi, qi, pi, qi, pi, qi),
                                         _mm256_setr_epi32(0, 0, 0, 1, 0, 2, 0, 3));
  const __m256i lanes = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(kAppendLanes[bits].data()));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm256_permutevar8x32_epi32(pairs, lanes));
  return static_cast<unsigned>(std::popcount(bits));
}

/// Same, the pairs (p, idx[t]): for spheres gathered from several runs.
inline unsigned append4_indexed(std::pair<std::uint32_t, std::uint32_t>* out, std::uint32_t p,
                                const std::uint32_t* idx, unsigned bits) {
  const __m128i pv = _mm_set1_epi32(static_cast<std::int32_t>(p));
  const __m128i iv = _mm_loadu_si128(reinterpret_cast<const __m128i*>(idx));
  const __m256i pairs = _mm256_set_m128i(_mm_unpackhi_epi32(pv, iv), _mm_unpacklo_epi32(pv, iv));
  const __m256i lanes = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(kAppendLanes[bits].data()));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm256_permutevar8x32_epi32(pairs, lanes));
  return static_cast<unsigned>(std::popcount(bits));
}
#else
inline constexpr bool kOverlap4 = false;

template <int D, Boundary B>
inline unsigned overlap4(const Sphere<D>& p, const Sphere<D>* s, const Extent<D>& box) {
  unsigned bits = 0;
  for (unsigned t = 0; t < 4; ++t) bits |= static_cast<unsigned>(overlap<D, B>(p, s[t], box)) << t;
  return bits;
}

template <int D, Boundary B, class Arrays>
inline unsigned overlap4_soa(const Sphere<D>& p, const Arrays& a, std::uint32_t t, const Extent<D>& box) {
  unsigned bits = 0;
  for (unsigned u = 0; u < 4; ++u) {
    Sphere<D> q;
    for (int k = 0; k < D; ++k) q.x[k] = a[k][t + u];
    q.r = a[D][t + u];
    bits |= static_cast<unsigned>(overlap<D, B>(p, q, box)) << u;
  }
  return bits;
}

template <int D, unsigned Periodic>
inline unsigned overlap4_pairs(const Sphere<D>* s, const std::uint32_t* first, const std::uint32_t* second,
                               const Extent<D>& box) {
  unsigned bits = 0;
  for (unsigned t = 0; t < 4; ++t)
    bits |= static_cast<unsigned>(overlap_axes<D, Periodic>(s[first[t]], s[second[t]], box)) << t;
  return bits;
}

inline unsigned compress4(std::uint32_t* out, const std::uint32_t* idx, unsigned bits) {
  unsigned n = 0;
  for (; bits != 0; bits &= bits - 1) out[n++] = idx[std::countr_zero(bits)];
  return n;
}

inline unsigned append4(std::pair<std::uint32_t, std::uint32_t>* out, std::uint32_t p, std::uint32_t q,
                        unsigned bits) {
  unsigned n = 0;
  for (; bits != 0; bits &= bits - 1) out[n++] = {p, q + static_cast<std::uint32_t>(std::countr_zero(bits))};
  return n;
}

inline unsigned append4_indexed(std::pair<std::uint32_t, std::uint32_t>* out, std::uint32_t p,
                                const std::uint32_t* idx, unsigned bits) {
  unsigned n = 0;
  for (; bits != 0; bits &= bits - 1) out[n++] = {p, idx[std::countr_zero(bits)]};
  return n;
}
#endif

}  // namespace hgrid::detail
