// The cost model over a packing's density field (density_field.hpp;
// docs/MODEL.md section 14).
#include "hgridlab/model/density_field.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "hgridlab/base/error.hpp"
#include "hgridlab/grid/geometry.hpp"

namespace hgrid {

namespace {

/// A cumulative (summed-area) table of weights binned on a regular grid over
/// the box, read at any real corner by multilinear interpolation (each bin's
/// weight spread evenly over it) and across periodic axes by whole turns.
class Cumulative {
 public:
  Cumulative(const FieldBox& box, double bin, std::size_t max_bins) : box_(box) {
    double cells = 1;
    for (int k = 0; k < box.d; ++k) cells *= std::max(1.0, std::round(box.side[k] / bin));
    if (cells > double(max_bins)) bin *= std::pow(cells / double(max_bins), 1.0 / box.d) * 1.0001;
    std::size_t stride = 1;
    for (int k = 0; k < box.d; ++k) {
      n_[k] = static_cast<std::size_t>(std::max(1.0, std::round(box.side[k] / bin)));
      b_[k] = box.side[k] / double(n_[k]);
      stride_[k] = stride;
      stride *= n_[k] + 1;
    }
    c_.assign(stride, 0.0);
  }

  void add(const double* x, double w) {
    std::size_t at = 0;
    for (int k = 0; k < box_.d; ++k) {
      const auto i = std::min<std::size_t>(n_[k] - 1, static_cast<std::size_t>(std::max(0.0, x[k] / b_[k])));
      at += (i + 1) * stride_[k];  // row 0 of each axis stays the zero border
    }
    c_[at] += w;
  }

  void accumulate() {
    for (int k = 0; k < box_.d; ++k) {
      const std::size_t block = stride_[k] * (n_[k] + 1);
      for (std::size_t outer = 0; outer < c_.size(); outer += block)
        for (std::size_t at = outer + stride_[k]; at < outer + block; ++at) c_[at] += c_[at - stride_[k]];
    }
  }

  /// Weight in the axis-aligned box [lo, hi] (hi - lo >= 0 per axis).
  double sum(const double* lo, const double* hi) const {
    double total = 0;
    const int corners = 1 << box_.d;
    for (int c = 0; c < corners; ++c) {
      double u[3];
      int lows = 0;
      for (int k = 0; k < box_.d; ++k) {
        const bool high = (c >> k) & 1;
        u[k] = (high ? hi[k] : lo[k]) / b_[k];
        lows += !high;
      }
      total += (lows % 2 ? -1.0 : 1.0) * below(u);
    }
    return total;
  }

  double bin(int k) const { return b_[k]; }

 private:
  /// Weight in (-inf, u] (bin units): whole turns on periodic axes, clipped
  /// to the box on walled ones.
  double below(const double* u) const {
    double terms_w[3][2], terms_v[3][2];
    int count[3];
    for (int k = 0; k < box_.d; ++k) {
      const double n = double(n_[k]);
      if (box_.periodic[k]) {
        const double q = std::floor(u[k] / n), rem = u[k] - q * n;
        count[k] = 0;
        if (q != 0) terms_w[k][count[k]] = q, terms_v[k][count[k]++] = n;
        terms_w[k][count[k]] = 1, terms_v[k][count[k]++] = rem;
      } else {
        count[k] = 1;
        terms_w[k][0] = 1;
        terms_v[k][0] = std::clamp(u[k], 0.0, n);
      }
    }
    double total = 0;
    int idx[3] = {0, 0, 0};
    while (true) {
      double w = 1, v[3];
      for (int k = 0; k < box_.d; ++k) w *= terms_w[k][idx[k]], v[k] = terms_v[k][idx[k]];
      total += w * interpolate(v);
      int k = 0;
      while (k < box_.d && ++idx[k] == count[k]) idx[k++] = 0;
      if (k == box_.d) break;
    }
    return total;
  }

  /// The table at real v (0 <= v_k <= n_k), multilinear between lattice points.
  double interpolate(const double* v) const {
    std::size_t base = 0;
    double t[3];
    for (int k = 0; k < box_.d; ++k) {
      const std::size_t i = std::min<std::size_t>(n_[k] - 1, static_cast<std::size_t>(v[k]));
      t[k] = std::clamp(v[k] - double(i), 0.0, 1.0);
      base += i * stride_[k];
    }
    double total = 0;
    for (int c = 0; c < (1 << box_.d); ++c) {
      double w = 1;
      std::size_t at = base;
      for (int k = 0; k < box_.d; ++k) {
        const bool up = (c >> k) & 1;
        w *= up ? t[k] : 1 - t[k];
        at += up ? stride_[k] : 0;
      }
      if (w != 0) total += w * c_[at];
    }
    return total;
  }

  FieldBox box_;
  std::size_t n_[3] = {1, 1, 1}, stride_[3] = {0, 0, 0};
  double b_[3] = {1, 1, 1};
  std::vector<double> c_;
};

int level_of(double r, const std::vector<double>& sizes) {
  const auto it = std::lower_bound(sizes.begin(), sizes.end(), 2 * r);
  return static_cast<int>(std::min<std::ptrdiff_t>(it - sizes.begin(), std::ptrdiff_t(sizes.size()) - 1));
}

}  // namespace

DensityField::DensityField(std::span<const double> positions, std::span<const double> radii, const FieldBox& box,
                           const FieldOptions& opt)
    : box_(box), opt_(opt), pos_(positions.begin(), positions.end()), radii_(radii.begin(), radii.end()) {
  const int d = box.d;
  if (d != 2 && d != 3) throw InputError("d", "must be 2 or 3 (got " + std::to_string(d) + ")");
  if (radii_.empty()) throw InputError("radii", "no particles");
  if (pos_.size() != radii_.size() * std::size_t(d))
    throw InputError("positions", "must hold d = " + std::to_string(d) + " coordinates per radius");
  if (!(opt.bins_per_window >= 1 && std::isfinite(opt.bins_per_window)))
    throw InputError("bins_per_window", "must be finite and >= 1");
  double volume = 1;
  for (int k = 0; k < d; ++k) {
    if (!(std::isfinite(box.side[k]) && box.side[k] > 0)) throw InputError("box", "every side must be finite and > 0");
    volume *= box.side[k];
  }
  double spheres = 0;
  for (std::size_t i = 0; i < radii_.size(); ++i) {
    if (!(std::isfinite(radii_[i]) && radii_[i] > 0)) throw InputError("radii", "every radius must be finite and > 0");
    spheres += ball_volume(d, radii_[i]);
    for (int k = 0; k < d; ++k) {
      double& x = pos_[i * d + k];
      if (!std::isfinite(x)) throw InputError("positions", "every coordinate must be finite");
      if (box.periodic[k]) x -= box.side[k] * std::floor(x / box.side[k]);
      else x = std::clamp(x, 0.0, box.side[k]);
    }
  }
  box_nu_ = spheres / volume;
  const std::size_t n = radii_.size(), stride = std::max<std::size_t>(1, (n + opt.max_samples - 1) / opt.max_samples);
  for (std::size_t i = 0; i < n; i += stride) samples_.push_back(i);
}

std::vector<double> DensityField::factors(const ModelParams& p, const std::vector<double>& sizes) const {
  const int d = box_.d, L = static_cast<int>(sizes.size());
  const Empirical dist(radii_);
  ModelParams mp = p;
  mp.d = d;
  mp.nu = std::min(1.0, box_nu_);
  const ModelResult base = evaluate_model(dist, mp, sizes);
  double volume = 1;
  for (int k = 0; k < d; ++k) volume *= box_.side[k];
  std::vector<int> level(radii_.size());
  std::vector<double> count(L, 0.0);
  for (std::size_t i = 0; i < radii_.size(); ++i) count[level[i] = level_of(radii_[i], sizes)] += 1;
  const double bin = 2 * sizes.front() / opt_.bins_per_window;
  std::vector<double> num(std::size_t(L) * L, 0.0), den(std::size_t(L) * L, 0.0);
  for (int j = 0; j < L; ++j) {
    if (count[j] == 0) continue;
    bool used = false;
    for (int h = 0; h < L; ++h) used |= base.T_cd_pair[std::size_t(h) * L + j] > 0;
    if (!used) continue;
    Cumulative table(box_, bin, opt_.max_bins);
    for (std::size_t i = 0; i < radii_.size(); ++i)
      if (level[i] == j) table.add(&pos_[i * d], 1.0);
    table.accumulate();
    const double n_j = count[j] / volume;
    for (std::size_t i : samples_) {
      const int h = level[i];
      const std::size_t at = std::size_t(h) * L + j;
      if (!(base.T_cd_pair[at] > 0)) continue;
      const double w = h == j ? 3 * sizes[j] : 2 * sizes[j] + 2 * radii_[i];
      double lo[3], hi[3];
      for (int k = 0; k < d; ++k) lo[k] = pos_[i * d + k] - w / 2, hi[k] = pos_[i * d + k] + w / 2;
      num[at] += table.sum(lo, hi) - (h == j ? 1.0 : 0.0);
      den[at] += n_j * std::pow(w, d);
    }
  }
  std::vector<double> F(std::size_t(L) * L, 0.0);
  for (std::size_t at = 0; at < F.size(); ++at)
    if (base.T_cd_pair[at] > 0) F[at] = den[at] > 0 ? std::max(0.0, num[at]) / den[at] : 1.0;
  return F;
}

FieldResult DensityField::evaluate(const ModelParams& p, const std::vector<double>& sizes) const {
  const int L = static_cast<int>(sizes.size());
  const Empirical dist(radii_);
  ModelParams mp = p;
  mp.d = box_.d;
  mp.nu = std::min(1.0, box_nu_);
  FieldResult out;
  ModelResult& r = out.model;
  r = evaluate_model(dist, mp, sizes);
  const std::vector<double> F = factors(p, sizes);
  const double homogeneous = r.T_cd_over_N;
  r.T_cd_over_N = 0;
  for (int h = 0; h < L; ++h) {
    r.T_cd[h] = 0;
    for (int j = 0; j < L; ++j) {
      double& t = r.T_cd_pair[std::size_t(h) * L + j];
      t *= F[std::size_t(h) * L + j];
      r.T_cd[h] += t;
    }
    r.T_cd_over_N += r.T_cd[h];
  }
  r.T_over_N = r.T_cd_over_N + p.K * r.T_ca_over_N;
  out.effective_nu = homogeneous > 0 ? mp.nu * r.T_cd_over_N / homogeneous : mp.nu;
  return out;
}

FieldSummary DensityField::summary(double window) const {
  if (!(window > 0 && std::isfinite(window))) throw InputError("window", "must be finite and > 0");
  const int d = box_.d;
  FieldSummary s;
  s.window = window;
  s.box_nu = box_nu_;
  Cumulative table(box_, window / opt_.bins_per_window, opt_.max_bins);
  for (std::size_t i = 0; i < radii_.size(); ++i) table.add(&pos_[i * d], ball_volume(d, radii_[i]));
  table.accumulate();
  for (std::size_t i : samples_) {
    double lo[3], hi[3], wv = 1;
    for (int k = 0; k < d; ++k) {
      lo[k] = pos_[i * d + k] - window / 2, hi[k] = pos_[i * d + k] + window / 2;
      // The particles' own density: the window's part inside a walled axis.
      wv *= box_.periodic[k] ? window : std::min(hi[k], box_.side[k]) - std::max(lo[k], 0.0);
    }
    const double nu = std::max(0.0, table.sum(lo, hi) - ball_volume(d, radii_[i])) / wv;
    s.mean_nu += nu;
    const auto b = static_cast<std::size_t>(nu / FieldSummary::kHistogramBin);
    if (s.histogram.size() <= b) s.histogram.resize(b + 1, 0.0);
    s.histogram[b] += 1;
  }
  s.mean_nu /= double(samples_.size());
  for (double& h : s.histogram) h /= double(samples_.size());
  // Empty cells of side `window`: the box cut into whole cells per axis.
  std::size_t cells = 1, n[3] = {1, 1, 1};
  for (int k = 0; k < d; ++k) cells *= n[k] = std::max<std::size_t>(1, std::size_t(box_.side[k] / window));
  if (cells <= opt_.max_bins) {
    std::vector<unsigned char> full(cells, 0);
    for (std::size_t i = 0; i < radii_.size(); ++i) {
      std::size_t at = 0, stride = 1;
      for (int k = 0; k < d; ++k) {
        const auto c = std::min(n[k] - 1, std::size_t(pos_[i * d + k] / box_.side[k] * double(n[k])));
        at += c * stride;
        stride *= n[k];
      }
      full[at] = 1;
    }
    s.empty_fraction = 1.0 - double(std::count(full.begin(), full.end(), 1)) / double(cells);
  }
  return s;
}

}  // namespace hgrid
