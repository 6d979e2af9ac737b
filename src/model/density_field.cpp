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

  /// Every weight back to 0 (the layout kept: no allocation).
  void clear() { std::fill(c_.begin(), c_.end(), 0.0); }

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
    : opt_(opt) {
  if (!(opt.bins_per_window >= 1 && std::isfinite(opt.bins_per_window)))
    throw InputError("bins_per_window", "must be finite and >= 1");
  frames_.push_back(make_frame(positions, radii, box));
  radii_ = frames_.back().radii;
  all_ = frames_.back().dist;
}

void DensityField::add_frame(std::span<const double> positions, std::span<const double> radii, const FieldBox& box) {
  if (box.d != d()) throw InputError("d", "every snapshot must have the dimension of the first");
  frames_.push_back(make_frame(positions, radii, box));
  radii_.insert(radii_.end(), radii.begin(), radii.end());
  all_ = std::make_shared<const Empirical>(radii_);
}

DensityField::Frame DensityField::make_frame(std::span<const double> positions, std::span<const double> radii,
                                             const FieldBox& box) const {
  const int d = box.d;
  if (d != 2 && d != 3) throw InputError("d", "must be 2 or 3 (got " + std::to_string(d) + ")");
  Frame f{box, std::vector<double>(positions.begin(), positions.end()), std::vector<double>(radii.begin(), radii.end()),
          {}, 0, 1};
  if (f.radii.empty()) throw InputError("radii", "no particles");
  if (f.pos.size() != f.radii.size() * std::size_t(d))
    throw InputError("positions", "must hold d = " + std::to_string(d) + " coordinates per radius");
  for (int k = 0; k < d; ++k) {
    if (!(std::isfinite(box.side[k]) && box.side[k] > 0)) throw InputError("box", "every side must be finite and > 0");
    f.volume *= box.side[k];
  }
  for (std::size_t i = 0; i < f.radii.size(); ++i) {
    if (!(std::isfinite(f.radii[i]) && f.radii[i] > 0)) throw InputError("radii", "every radius must be finite and > 0");
    f.spheres += ball_volume(d, f.radii[i]);
    for (int k = 0; k < d; ++k) {
      double& x = f.pos[i * d + k];
      if (!std::isfinite(x)) throw InputError("positions", "every coordinate must be finite");
      if (box.periodic[k]) x -= box.side[k] * std::floor(x / box.side[k]);
      else x = std::clamp(x, 0.0, box.side[k]);
    }
  }
  const std::size_t n = f.radii.size(), stride = std::max<std::size_t>(1, (n + opt_.max_samples - 1) / opt_.max_samples);
  for (std::size_t i = 0; i < n; i += stride) f.samples.push_back(i);
  f.dist = std::make_shared<const Empirical>(f.radii);
  return f;
}

double DensityField::box_nu() const {
  double spheres = 0, volume = 0;
  for (const Frame& f : frames_) spheres += f.spheres, volume += f.volume;
  return spheres / volume;
}

double DensityField::volume() const {
  double v = 0;
  for (const Frame& f : frames_) v += f.volume;
  return v / double(frames_.size());
}

ModelResult DensityField::frame_model(const Frame& f, const ModelParams& p, const std::vector<double>& sizes) const {
  ModelParams mp = p;
  mp.d = f.box.d;
  mp.nu = std::min(1.0, f.spheres / f.volume);
  return evaluate_model(*f.dist, mp, sizes);
}

std::vector<double> DensityField::factors(const ModelParams& p, const std::vector<double>& sizes,
                                          std::size_t frame) const {
  const Frame& f = frames_.at(frame);
  return frame_factors(f, frame_model(f, p, sizes), sizes);
}

std::vector<double> DensityField::frame_factors(const Frame& fr, const ModelResult& base,
                                                const std::vector<double>& sizes) const {
  const int d = fr.box.d, L = static_cast<int>(sizes.size());
  std::vector<int> level(fr.radii.size());
  std::vector<double> count(L, 0.0);
  std::vector<std::vector<std::size_t>> members(L);
  for (std::size_t i = 0; i < fr.radii.size(); ++i) {
    count[level[i] = level_of(fr.radii[i], sizes)] += 1;
    members[level[i]].push_back(i);
  }
  const double bin = 2 * sizes.front() / opt_.bins_per_window;
  std::vector<double> num(std::size_t(L) * L, 0.0), den(std::size_t(L) * L, 0.0);
  Cumulative table(fr.box, bin, opt_.max_bins);  // one table, refilled per level
  for (int j = 0; j < L; ++j) {
    if (count[j] == 0) continue;
    bool used = false;
    for (int h = 0; h < L; ++h) used |= base.T_cd_pair[std::size_t(h) * L + j] > 0;
    if (!used) continue;
    table.clear();
    for (std::size_t i : members[j]) table.add(&fr.pos[i * d], 1.0);
    table.accumulate();
    const double n_j = count[j] / fr.volume;
    for (std::size_t i : fr.samples) {
      const int h = level[i];
      const std::size_t at = std::size_t(h) * L + j;
      if (!(base.T_cd_pair[at] > 0)) continue;
      const double w = h == j ? 3 * sizes[j] : 2 * sizes[j] + 2 * fr.radii[i];
      double lo[3], hi[3];
      for (int k = 0; k < d; ++k) lo[k] = fr.pos[i * d + k] - w / 2, hi[k] = fr.pos[i * d + k] + w / 2;
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
  const double total = double(radii_.size());
  FieldResult out;
  ModelResult& r = out.model;
  for (const Frame& f : frames_) {
    ModelResult m = frame_model(f, p, sizes);
    const std::vector<double> F = frame_factors(f, m, sizes);
    m.T_cd_over_N = 0;
    for (int h = 0; h < L; ++h) {
      m.T_cd[h] = 0;
      for (int j = 0; j < L; ++j) {
        double& t = m.T_cd_pair[std::size_t(h) * L + j];
        t *= F[std::size_t(h) * L + j];
        m.T_cd[h] += t;
      }
      m.T_cd_over_N += m.T_cd[h];
    }
    m.T_over_N = m.T_cd_over_N + p.K * m.T_ca_over_N;
    // Per particle over all snapshots: each weighs by its particles.
    const double w = double(f.radii.size()) / total;
    if (frames_.size() == 1) {
      r = std::move(m);
      break;
    }
    if (r.sizes.empty()) {
      r = m;
      r.T_over_N = r.T_cd_over_N = r.T_ca_over_N = 0;
      for (auto* v : {&r.P, &r.m, &r.T_cd, &r.T_ca, &r.T_cd_pair}) std::fill(v->begin(), v->end(), 0.0);
    }
    r.T_over_N += w * m.T_over_N;
    r.T_cd_over_N += w * m.T_cd_over_N;
    r.T_ca_over_N += w * m.T_ca_over_N;
    for (std::size_t k = 0; k < r.P.size(); ++k) {
      r.P[k] += w * m.P[k], r.m[k] += w * m.m[k], r.T_cd[k] += w * m.T_cd[k], r.T_ca[k] += w * m.T_ca[k];
    }
    for (std::size_t k = 0; k < r.T_cd_pair.size(); ++k) r.T_cd_pair[k] += w * m.T_cd_pair[k];
  }
  // The homogeneous nu with the same count: the paper's model for every
  // radius at the snapshots' nu, scaled to the field's count.
  ModelParams mp = p;
  mp.d = d();
  mp.nu = std::min(1.0, box_nu());
  const double homogeneous = evaluate_model(*all_, mp, sizes).T_cd_over_N;
  out.effective_nu = homogeneous > 0 ? mp.nu * r.T_cd_over_N / homogeneous : mp.nu;
  return out;
}

FieldSummary DensityField::summary(double window) const {
  if (!(window > 0 && std::isfinite(window))) throw InputError("window", "must be finite and > 0");
  FieldSummary s;
  s.window = window;
  s.box_nu = box_nu();
  std::size_t samples = 0;
  for (const Frame& fr : frames_) {
    const int d = fr.box.d;
    Cumulative table(fr.box, window / opt_.bins_per_window, opt_.max_bins);
    for (std::size_t i = 0; i < fr.radii.size(); ++i) table.add(&fr.pos[i * d], ball_volume(d, fr.radii[i]));
    table.accumulate();
    for (std::size_t i : fr.samples) {
      double lo[3], hi[3], wv = 1;
      for (int k = 0; k < d; ++k) {
        lo[k] = fr.pos[i * d + k] - window / 2, hi[k] = fr.pos[i * d + k] + window / 2;
        // The particles' own density: the window's part inside a walled axis.
        wv *= fr.box.periodic[k] ? window : std::min(hi[k], fr.box.side[k]) - std::max(lo[k], 0.0);
      }
      const double nu = std::max(0.0, table.sum(lo, hi) - ball_volume(d, fr.radii[i])) / wv;
      s.mean_nu += nu;
      const auto b = static_cast<std::size_t>(nu / FieldSummary::kHistogramBin);
      if (s.histogram.size() <= b) s.histogram.resize(b + 1, 0.0);
      s.histogram[b] += 1;
      ++samples;
    }
    // Empty cells of side `window`: the box cut into whole cells per axis.
    std::size_t cells = 1, n[3] = {1, 1, 1};
    for (int k = 0; k < d; ++k) cells *= n[k] = std::max<std::size_t>(1, std::size_t(fr.box.side[k] / window));
    if (cells <= opt_.max_bins) {
      std::vector<unsigned char> full(cells, 0);
      for (std::size_t i = 0; i < fr.radii.size(); ++i) {
        std::size_t at = 0, stride = 1;
        for (int k = 0; k < d; ++k) {
          const auto c = std::min(n[k] - 1, std::size_t(fr.pos[i * d + k] / fr.box.side[k] * double(n[k])));
          at += c * stride;
          stride *= n[k];
        }
        full[at] = 1;
      }
      s.empty_fraction += (1.0 - double(std::count(full.begin(), full.end(), 1)) / double(cells)) / double(frames_.size());
    }
  }
  s.mean_nu /= double(samples);
  for (double& h : s.histogram) h /= double(samples);
  return s;
}

}  // namespace hgrid
