// Quality figures of a packing (hgrid info, generator attributes).
#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <vector>

#include "hgridlab/packing/detail/gen_common.hpp"
#include "hgridlab/packing/detail/gen_pairs.hpp"
#include "hgridlab/grid/tilted.hpp"
#include "hgridlab/packing/generate.hpp"

namespace hgrid {
namespace {

/// Volume (3D) or area (2D) of a ball of radius r centred at 0 between the
/// planes t = a and t = b.
double ball_section(int d, double r, double a, double b) {
  a = std::clamp(a, -r, r);
  b = std::clamp(b, -r, r);
  if (b <= a) return 0;
  if (d == 3) {
    auto F = [r](double t) { return M_PI * (r * r * t - t * t * t / 3); };
    return F(b) - F(a);
  }
  auto F = [r](double t) { return t * std::sqrt(std::max(0.0, r * r - t * t)) + r * r * std::asin(t / r); };
  return F(b) - F(a);
}

template <int D, Boundary B>
void pair_figures(const Packing& p, PackingQuality& q) {
  auto spheres = p.spheres<D>();
  for (auto& s : spheres) s.r *= 1 + kContactGap;
  std::uint64_t contacts = 0;
  std::vector<double> rels;  // summed in sorted order: the mean does not depend on the grid's pair order
  const Extent<D> box = p.extent<D>();
  detail::for_each_overlapping<D, B>(std::span<const Sphere<D>>(spheres), box, [&](std::uint32_t i, std::uint32_t j) {
    std::array<double, D> a, b;
    for (int k = 0; k < D; ++k) {
      a[k] = p.positions[i * D + k];
      b[k] = p.positions[j * D + k];
    }
    const double rs = p.radii[i] + p.radii[j];
    const double dist = std::sqrt(detail::dist2<D, B>(a, b, box));
    ++contacts;
    if (dist < rs) {
      const double rel = (rs - dist) / rs;
      ++q.overlapping_pairs;
      rels.push_back(rel);
      q.max_rel_overlap = std::max(q.max_rel_overlap, rel);
    }
  });
  if constexpr (B == Boundary::walls) {
    for (std::size_t i = 0; i < p.size(); ++i)
      for (int k = 0; k < D; ++k) {
        const double x = p.positions[i * D + k], r = p.radii[i];
        const double over = std::max(r - x, x + r - p.box[k]);
        if (over > 0) q.max_rel_overlap = std::max(q.max_rel_overlap, over / r);
      }
  }
  std::sort(rels.begin(), rels.end());
  const double sum = std::accumulate(rels.begin(), rels.end(), 0.0);
  q.mean_rel_overlap = q.overlapping_pairs ? sum / static_cast<double>(q.overlapping_pairs) : 0.0;
  q.mean_contacts = p.size() ? 2.0 * static_cast<double>(contacts) / static_cast<double>(p.size()) : 0.0;
}

/// The same figures for a tilted box: its grid, its minimum image.
template <int D>
void tilted_pair_figures(const Packing& p, PackingQuality& q) {
  auto spheres = p.spheres<D>();
  for (auto& s : spheres) s.r *= 1 + kContactGap;
  const TiltedBox<D> box = p.tilted_box<D>();
  std::uint64_t contacts = 0;
  std::vector<double> rels;
  if (spheres.size() < 2) return;
  double lo = spheres[0].r, hi = lo;
  for (const auto& s : spheres) lo = std::min(lo, s.r), hi = std::max(hi, s.r);
  const TiltedHGrid<D> grid(std::span<const Sphere<D>>(spheres), box,
                            GridParams{doubling_sizes(lo, hi), Search::bottom_up});
  grid.for_each_pair([&](std::uint32_t i, std::uint32_t j) {
    const auto& a = spheres[i].x;
    const auto& b = spheres[j].x;
    const double rs = p.radii[i] + p.radii[j];
    const double dist = std::sqrt(detail::tilted_dist2<D>(box, a, b, detail::nearest_shift<D>(box, a, b)));
    ++contacts;
    if (dist < rs) {
      ++q.overlapping_pairs;
      rels.push_back((rs - dist) / rs);
      q.max_rel_overlap = std::max(q.max_rel_overlap, rels.back());
    }
  });
  std::sort(rels.begin(), rels.end());
  const double sum = std::accumulate(rels.begin(), rels.end(), 0.0);
  q.mean_rel_overlap = q.overlapping_pairs ? sum / static_cast<double>(q.overlapping_pairs) : 0.0;
  q.mean_contacts = p.size() ? 2.0 * static_cast<double>(contacts) / static_cast<double>(p.size()) : 0.0;
}

void slab_figures(const Packing& p, PackingQuality& q) {
  const int d = p.d;
  const std::size_t n = p.size();
  // Size bands: equal shares of the particle volume, by radius.
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return p.radii[a] < p.radii[b]; });
  std::vector<int> band(n);
  double total = 0;
  for (double r : p.radii) total += std::pow(r, d);
  double cum = 0;
  for (auto i : order) {
    band[i] = std::min(kSizeBands - 1, static_cast<int>(kSizeBands * cum / total));
    cum += std::pow(p.radii[i], d);
  }
  double box_vol = 1;
  for (int k = 0; k < d; ++k) box_vol *= p.box[k];
  q.slab_nu.assign(d, std::vector<double>(kSlabs, 0.0));
  std::vector<std::vector<std::vector<double>>> bnu(
      kSizeBands, std::vector<std::vector<double>>(d, std::vector<double>(kSlabs, 0.0)));
  for (int k = 0; k < d; ++k) {
    const double w = p.box[k] / kSlabs;
    const double slab_vol = box_vol / kSlabs;
    for (std::size_t i = 0; i < n; ++i) {
      const double c = p.positions[i * d + k], r = p.radii[i];
      const int s0 = static_cast<int>(std::floor((c - r) / w)), s1 = static_cast<int>(std::floor((c + r) / w));
      for (int s = s0; s <= s1; ++s) {
        int slab = s;
        if (p.boundary == Boundary::periodic) slab = ((s % kSlabs) + kSlabs) % kSlabs;
        else if (s < 0 || s >= kSlabs) continue;
        const double v = ball_section(d, r, s * w - c, (s + 1) * w - c) / slab_vol;
        q.slab_nu[k][slab] += v;
        bnu[band[i]][k][slab] += v;
      }
    }
  }
  auto worst = [&](const std::vector<std::vector<double>>& nu) {
    double dev = 0;
    for (const auto& axis : nu) {
      const double mean = std::accumulate(axis.begin(), axis.end(), 0.0) / kSlabs;
      for (double v : axis)
        if (mean > 0) dev = std::max(dev, std::abs(v / mean - 1));
    }
    return dev;
  };
  q.slab_max_dev = worst(q.slab_nu);
  q.band_slab_max_dev.clear();
  for (int b = 0; b < kSizeBands; ++b) q.band_slab_max_dev.push_back(worst(bnu[b]));
  // Counting noise: a slab's share of sum V_i is binomial with p = 1/S.
  std::vector<double> v1(kSizeBands + 1, 0.0), v2(kSizeBands + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double v = std::pow(p.radii[i], d);
    for (int b : {band[i], kSizeBands}) v1[b] += v, v2[b] += v * v;
  }
  const auto noise = [](double s1, double s2) {
    return s1 > 0 ? std::sqrt((1.0 - 1.0 / kSlabs) * kSlabs * s2) / s1 : 0.0;
  };
  q.slab_noise = noise(v1[kSizeBands], v2[kSizeBands]);
  q.band_slab_noise.clear();
  for (int b = 0; b < kSizeBands; ++b) q.band_slab_noise.push_back(noise(v1[b], v2[b]));
}

/// Kolmogorov distribution tail Q(lambda) = 2 sum (-1)^(k-1) exp(-2 k^2 lambda^2).
double kolmogorov_q(double lambda) {
  if (lambda < 0.2) return 1.0;
  double s = 0;
  for (int k = 1; k <= 100; ++k) s += (k % 2 ? 2 : -2) * std::exp(-2.0 * k * k * lambda * lambda);
  return std::clamp(s, 0.0, 1.0);
}

void fit_figures(const Packing& p, const Distribution& dist, PackingQuality& q) {
  std::vector<double> r = p.radii;
  std::sort(r.begin(), r.end());
  const double n = static_cast<double>(r.size());
  double dmax = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const double F = dist.cdf(r[i]);
    dmax = std::max({dmax, std::abs(F - i / n), std::abs((i + 1) / n - F)});
  }
  q.ks_distance = dmax;
  const double sn = std::sqrt(n);
  q.ks_pvalue = kolmogorov_q((sn + 0.12 + 0.11 / sn) * dmax);  // Stephens (1970)
  constexpr int kBins = 20;
  const double lo = dist.r_min(), hi = std::max(dist.r_max(), lo * (1 + 1e-12));
  q.hist_edges.clear();
  for (int b = 0; b <= kBins; ++b) q.hist_edges.push_back(lo * std::pow(hi / lo, static_cast<double>(b) / kBins));
  q.hist_edges.back() = hi;
  q.hist_count.assign(kBins, 0.0);
  q.hist_expected.assign(kBins, 0.0);
  for (double v : r) {
    const auto it = std::upper_bound(q.hist_edges.begin(), q.hist_edges.end(), v);
    const int b = std::clamp(static_cast<int>(it - q.hist_edges.begin()) - 1, 0, kBins - 1);
    q.hist_count[b] += 1;
  }
  for (int b = 0; b < kBins; ++b)
    q.hist_expected[b] = n * (dist.cdf(q.hist_edges[b + 1]) - (b == 0 ? 0.0 : dist.cdf(q.hist_edges[b])));
}

}  // namespace

PackingQuality assess_packing(const Packing& p, const Distribution* dist, bool pairs) {
  PackingQuality q;
  q.nu = p.packing_fraction();
  if (!pairs) {
    q.max_rel_overlap = q.mean_rel_overlap = q.mean_contacts = -1;
  } else if (p.tilted())
    p.d == 2 ? tilted_pair_figures<2>(p, q) : tilted_pair_figures<3>(p, q);
  else if (p.d == 2)
    p.boundary == Boundary::walls ? pair_figures<2, Boundary::walls>(p, q) : pair_figures<2, Boundary::periodic>(p, q);
  else
    p.boundary == Boundary::walls ? pair_figures<3, Boundary::walls>(p, q) : pair_figures<3, Boundary::periodic>(p, q);
  if (p.tilted()) {  // slabs between lattice planes: the mapped centres (grid/tilted_box.hpp) in the box of the lengths
    Packing m = p;
    m.tilt = {};
    const auto map = [&](auto box) {
      constexpr int D = std::tuple_size_v<decltype(box.length)>;
      for (std::size_t i = 0; i < m.size(); ++i) {
        std::array<double, D> x{};
        for (int a = 0; a < D; ++a) x[a] = p.positions[i * D + a];
        x = box.mapped(x);
        for (int a = 0; a < D; ++a) m.positions[i * D + a] = x[a];
      }
    };
    p.d == 2 ? map(p.tilted_box<2>()) : map(p.tilted_box<3>());
    slab_figures(m, q);
  } else {
    slab_figures(p, q);
  }
  if (dist) fit_figures(p, *dist, q);
  return q;
}

}  // namespace hgrid
