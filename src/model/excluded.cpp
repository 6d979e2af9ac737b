// Excluded-volume cost model (docs/MODEL.md section 8).
#include "hgridlab/model/excluded.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>

#include "hgridlab/base/error.hpp"
#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/model/detail/py_mixture.hpp"
#include "hgridlab/model/detail/py_numeric.hpp"
#include "hgridlab/model/detail/walls.hpp"
#include "hgridlab/model/detail/window.hpp"

namespace hgrid {

namespace {
constexpr int kPad = 4;                 // r-grid oversampling of the sine transform
constexpr double kMinBinProbability = 1e-300;

struct Bin {
  int level;
  double P, r_mean, sigma;  // probability, mean radius, diameter keeping the mean volume
};

struct Window {
  int bin, level_searched;
  double c, s, half;  // window_1d(c, s); 1/2 for the own level (pairs counted once)
};

// Walls: each window's random-centre count and cell accesses in the walled
// box (centres in their accessible region with the wall profiles, scans
// clipped), and the bulk excess scaled by the ratio of walled to bulk random
// counts, counting only scanning centres outside the layer `wall_pairs` spares.
void apply_walls(int d, const WallBox& box, WallPairs wall_pairs, double density, const std::vector<Bin>& bins,
                 const std::vector<detail::WallProfile>& prof, const std::vector<Window>& win,
                 const std::vector<double>& excess, const std::vector<double>& sizes, ModelResult& res) {
  const int L = static_cast<int>(sizes.size());
  // Scanning centres closer to a wall than this carry no pair excess.
  double layer = 0.0;
  if (wall_pairs == WallPairs::depleted_layer)
    for (const Bin& b : bins) layer = std::max(layer, b.r_mean);
  double volume = 1.0;
  for (int k = 0; k < d; ++k) volume *= box.extent[k];
  std::fill(res.T_cd_pair.begin(), res.T_cd_pair.end(), 0.0);
  std::fill(res.T_ca.begin(), res.T_ca.end(), 0.0);
  for (std::size_t w = 0; w < win.size(); ++w) {
    const Window& wi = win[w];
    const Bin& a = bins[wi.bin];
    const bool own = wi.level_searched == a.level;
    std::vector<detail::WallProfile> searched;
    std::vector<double> prob;
    double P_j = 0.0;
    for (std::size_t q = 0; q < bins.size(); ++q)
      if (bins[q].level == wi.level_searched) searched.push_back(prof[q]), prob.push_back(bins[q].P), P_j += bins[q].P;
    std::array<detail::AxisScan, 3> ax;
    for (int k = 0; k < d; ++k) {
      int same = 0;  // an earlier axis of the same length (a square or cubic box): the same scan
      while (same < k && box.extent[same] != box.extent[k]) ++same;
      ax[k] = same < k ? ax[same]
                       : detail::scan_axis(box.extent[k], prof[wi.bin], sizes[wi.level_searched], own,
                                           a.r_mean + 0.5 * sizes[wi.level_searched], searched, layer);
    }
    // Expected level-j centres in the scan per particle: all, and those seen
    // from a scanning centre outside the wall layers (the ones with excess).
    double random = 0.0, random_interior = 0.0;
    for (std::size_t q = 0; q < searched.size(); ++q) {
      double f = density * volume * prob[q], g = f;
      for (int k = 0; k < d; ++k) f *= ax[k].fraction[q], g *= ax[k].fraction_interior[q];
      random += f;
      random_interior += g;
    }
    const double bulk = density * P_j * std::pow(2.0 * wi.c + wi.s, d);
    const double scaled_excess = bulk > 0 ? excess[w] * random_interior / bulk : 0.0;
    res.T_cd_pair[a.level * L + wi.level_searched] += wi.half * a.P * (random + scaled_excess);
    double cells = 1.0;
    if (own) {  // own cell + the existing cells of the half stencil (first non-zero offset positive)
      cells = 0.0;
      const int count = d == 2 ? 9 : 27;
      for (int m = 0; m < count; ++m) {
        int o[3] = {m % 3 - 1, (m / 3) % 3 - 1, d == 3 ? m / 9 - 1 : 0};
        int first = 0;
        for (int k = 0; k < d && first == 0; ++k) first = o[k];
        if (first < 0) continue;
        double pr = 1.0;
        for (int k = 0; k < d; ++k) pr *= o[k] < 0 ? ax[k].p_below : (o[k] > 0 ? ax[k].p_above : 1.0);
        cells += pr;
      }
    } else {
      for (int k = 0; k < d; ++k) cells *= ax[k].cells;
    }
    res.T_ca[a.level] += a.P * cells;
  }
  res.T_ca_over_N = 0.0;
  for (double t : res.T_ca) res.T_ca_over_N += t;
}

std::size_t next_pow2(double x) {
  std::size_t n = 2;
  while (static_cast<double>(n) < x) n *= 2;
  return n;
}

// The contact step of h_bW, taken out of the transform and added back in r:
// s(r) = -1 inside contact (r < R), (g - 1) e^{-(r - R)/lambda} outside, where g
// is the Percus-Yevick contact value (PyMixture::contact_value). Its 3D Fourier
// transform, shat(k) = (4 pi / k) int r s(r) sin(kr) dr, in closed form.
struct ContactStep {
  double R, g, lambda;
  double operator()(double r) const { return r < R ? -1.0 : (g - 1.0) * std::exp(-(r - R) / lambda); }
  double transform(double k) const {
    const double kR = k * R;
    const double inside = -(std::sin(kR) - kR * std::cos(kR)) / (k * k);
    const std::complex<double> z(1.0 / lambda, -k);  // a - ik
    const double outside = (std::exp(std::complex<double>(0.0, kR)) * (1.0 / (z * z) + R / z)).imag();
    return 4.0 * std::numbers::pi / k * (inside + (g - 1.0) * outside);
  }
};

// Wall density profiles: the wall is a sphere kWallDiameter times the largest
// diameter, at a density too low to matter, in the same Percus-Yevick mixture
// (the wall limit of the mixture's big-particle structure). h_Wb(z) is
// tabulated for z = 0 .. kWallReach largest diameters from the wall.
constexpr double kWallDiameter = 20.0;
constexpr double kWallReach = 4.0;
constexpr double kWallPacking = 1e-12;  // (pi/6) rho_W sigma_W^3
constexpr double kWallDk = 0.25;        // wave-number step, in units of pi / reach
constexpr int kWallPad = 16;            // r-grid oversampling of the wall profiles' sine transform

std::vector<detail::WallProfile> wall_profiles(const std::vector<double>& rho, const std::vector<double>& sigma,
                                               const std::vector<Bin>& bins, const ExcludedOptions& opt) {
  const int B = static_cast<int>(rho.size());
  const double smax = *std::max_element(sigma.begin(), sigma.end());
  const double smin = *std::min_element(sigma.begin(), sigma.end());
  const double sw = kWallDiameter * smax, rw = kWallPacking * 6.0 / (std::numbers::pi * sw * sw * sw);
  std::vector<double> rho2 = rho, sig2 = sigma;
  rho2.push_back(rw);
  sig2.push_back(sw);
  const detail::PyMixture py(rho2, sig2);
  const double reach = 0.5 * sw + kWallReach * smax, kmax = opt.k_max / smin;
  const std::size_t N = next_pow2(kmax / (kWallDk * std::numbers::pi / reach) + 1.0);
  if (N > static_cast<std::size_t>(kMaxWaveNumbers) * 4)
    throw InputError("omega", "size ratio too large for the excluded-volume model with walls");
  const double dk = kmax / static_cast<double>(N);
  // The step at contact would be smeared over ~pi / kmax by the truncated
  // transform (part of the contact layer lost inside the wall): it is
  // transformed exactly instead, and only the continuous rest numerically.
  std::vector<ContactStep> step(B);
  for (int b = 0; b < B; ++b) step[b] = {0.5 * (sigma[b] + sw), py.contact_value(b, B), 0.5 * smin};
  std::vector<std::vector<double>> Y(B, std::vector<double>(N, 0.0)), y;
  std::vector<std::vector<double>> e(1, std::vector<double>(B + 1, 0.0));
  e[0][B] = 1.0;
  for (std::size_t m = 1; m < N; ++m) {
    const double k = m * dk;
    py.apply_h(k, e, y);
    for (int b = 0; b < B; ++b) Y[b][m] = k * (y[0][b] / std::sqrt(rho[b] * rw) - step[b].transform(k));
  }
  // The profiles' layers at contact are narrow: the r-grid is kWallPad times
  // finer than the wave numbers alone need (one class transformed at a time).
  const std::size_t Nf = N * kWallPad;
  const double dr = std::numbers::pi / (static_cast<double>(Nf) * dk);
  std::vector<detail::WallProfile> prof(B);
  std::vector<double> F;
  for (int b = 0; b < B; ++b) {
    F.assign(Nf, 0.0);
    std::copy(Y[b].begin(), Y[b].end(), F.begin());
    detail::sine_transform(F);
    prof[b].radius = bins[b].r_mean;
    prof[b].dz = dr;
    prof[b].contact = 0.5 * sigma[b];
    const auto nz = static_cast<std::size_t>(kWallReach * smax / dr);
    prof[b].h.resize(nz);
    for (std::size_t i = 0; i < nz; ++i) {
      const double r = 0.5 * sw + i * dr, t = r / dr;
      const auto n = static_cast<std::size_t>(t);
      if (n + 1 >= Nf) break;
      const double hn = F[n] / (n * dr), hn1 = F[n + 1] / ((n + 1) * dr);
      prof[b].h[i] = (hn + (t - n) * (hn1 - hn)) * dk / (2.0 * std::numbers::pi * std::numbers::pi) + step[b](r);
    }
  }
  return prof;
}

// Largest size ratio of the 2D model: its solver's work grows like omega^2
// per iteration (about 0.1 s at omega = 50 on one core), and the iteration
// stops converging at lower packing fractions as omega grows.
constexpr double kMaxDiscOmega = 50.0 * (1.0 + 1e-9);

// 2D: h_ab from the numerical Percus-Yevick solution for discs (no closed
// form). Per window: n_j int W h d^2y = int L_W(r) sum_b rho_b gamma_ab(r) dr
// - sum_b rho_b int_0^sigma_ab (1 + gamma_ab) L_W dr, as h = gamma + c with
// c = -(1 + gamma) inside contact and 0 outside.
std::vector<double> disc_excess(const std::vector<Bin>& bins, const std::vector<double>& rho,
                                const std::vector<double>& sigma, const std::vector<Window>& win, double nu,
                                const ExcludedOptions& opt, std::vector<detail::WallProfile>* prof) {
  const int B = static_cast<int>(bins.size());
  const double smin = *std::min_element(sigma.begin(), sigma.end());
  const double smax = *std::max_element(sigma.begin(), sigma.end());
  double r_out = 0.0;
  for (const Window& w : win) r_out = std::max(r_out, std::sqrt(2.0) * (w.c + w.s));
  detail::PyNumericGrid g;
  g.dr = opt.disc_dr * smin;
  g.max_iterations = kMaxDiscIterations;
  g.max_work = opt.disc_work_budget;
  // Walls: one more component, a disc kWallDiameter times the largest (its
  // radius on the r grid) at a negligible density, as in 3D.
  std::vector<double> rho_all = rho, sigma_all = sigma;
  const double wall_radius = g.dr * std::ceil(0.5 * kWallDiameter * smax / g.dr);
  if (prof) {
    rho_all.push_back(kWallPacking / (0.25 * std::numbers::pi * 4.0 * wall_radius * wall_radius));
    sigma_all.push_back(2.0 * wall_radius);
    r_out = std::max(r_out, wall_radius + kWallReach * smax);
  }
  g.r_out = r_out + 2.0 * g.dr;  // covers ceil(reach / dr) + 1 points
  g.range = r_out + opt.disc_range * smax;
  g.nk = static_cast<int>(std::ceil(opt.k_max / smin * g.range / std::numbers::pi));
  std::optional<detail::PyNumeric> py;
  try {
    py.emplace(2, rho_all, sigma_all, g, opt.on_iteration);
  } catch (const detail::PyWorkBudget& b) {
    char v[400];
    std::snprintf(v, sizeof v,
                  "the 2D excluded-volume model of these discs at nu = %.4g %s %.3g multiply-adds (~%.2g s): it "
                  "takes %.3g per iteration, up to %d iterations (~%.0f s); a budget of 0 (none) lets it try",
                  nu, b.refused_before ? "cannot be tried within" : "did not converge within", opt.disc_work_budget,
                  opt.disc_work_budget / kDiscWorkPerSecond, b.work_per_iteration, kMaxDiscIterations,
                  b.work_per_iteration * kMaxDiscIterations / kDiscWorkPerSecond);
    throw InputError("excluded-budget", v);
  } catch (const std::runtime_error&) {
    char v[32];
    std::snprintf(v, sizeof v, "%.4g", nu);
    throw InputError("nu", std::string("the Percus-Yevick iteration for these discs did not converge at nu = ") + v +
                               " (the 2D excluded-volume model reaches nu = 0.6 up to omega ~ 20, 0.45 at omega = 50)");
  }
  std::vector<double> excess(win.size(), 0.0);
  for (int a = 0; a < B; ++a) {
    std::vector<std::size_t> mine;
    std::vector<std::vector<double>> weight;
    int count = 1;
    for (std::size_t w = 0; w < win.size(); ++w) {
      if (win[w].bin != a) continue;
      mine.push_back(w);
      std::vector<double> wt(rho_all.size(), 0.0);
      for (int b = 0; b < B; ++b)
        if (bins[b].level == win[w].level_searched) wt[b] = rho[b];
      weight.push_back(std::move(wt));
      count = std::max(count, static_cast<int>(std::ceil(std::sqrt(2.0) * (win[w].c + win[w].s) / g.dr)) + 1);
    }
    const auto sums = py->gamma_sums(a, weight, count);
    for (std::size_t q = 0; q < mine.size(); ++q) {
      const Window& wi = win[mine[q]];
      const int nmax = std::min(count - 1, static_cast<int>(std::ceil(std::sqrt(2.0) * (wi.c + wi.s) / g.dr)));
      const std::vector<double> lw = detail::window_circle_lengths(wi.c, wi.s, g.dr, nmax);
      const auto L_at = [&](double r) {
        const double t = r / g.dr;
        const auto n = static_cast<int>(t);
        if (n >= nmax) return 0.0;
        return lw[n] + (t - n) * (lw[n + 1] - lw[n]);
      };
      double x = 0.0;
      for (int n = 1; n <= nmax; ++n) x += lw[n] * sums[q][n];
      x *= g.dr;
      for (int b = 0; b < B; ++b) {
        if (weight[q][b] == 0.0) continue;
        const std::vector<double>& gam = py->gamma_inside(a, b);
        const int m = static_cast<int>(gam.size()) - 2;  // nodes n dr, n = 0 .. m, then sigma_ab
        const double s_ab = 0.5 * (sigma[a] + sigma[b]), tail = s_ab - m * g.dr;
        double in = 0.0;
        for (int n = 1; n < m; ++n) in += (1.0 + gam[n]) * L_at(n * g.dr) * g.dr;
        const double last = (1.0 + gam[m]) * L_at(m * g.dr), end = (1.0 + gam[m + 1]) * L_at(s_ab);
        in += 0.5 * last * (m > 0 ? g.dr : 0.0) + 0.5 * (last + end) * tail;
        x -= rho[b] * in;
      }
      excess[mine[q]] = x;
    }
  }
  if (prof) {  // h_Wb at z = 0, dr, ... from the wall's surface: gamma_Wb(wall_radius + z)
    const auto n0 = static_cast<int>(std::lround(wall_radius / g.dr));
    const auto nz = static_cast<int>(kWallReach * smax / g.dr);
    std::vector<std::vector<double>> unit(B, std::vector<double>(rho_all.size(), 0.0));
    for (int b = 0; b < B; ++b) unit[b][b] = 1.0;
    const auto h = py->gamma_sums(B, unit, n0 + nz);
    prof->assign(B, {});
    for (int b = 0; b < B; ++b) {
      (*prof)[b].radius = bins[b].r_mean;
      (*prof)[b].dz = g.dr;
      (*prof)[b].h.assign(h[b].begin() + n0, h[b].end());
    }
  }
  return excess;
}
// Level totals and T/N from the per-pair counts.
ModelResult finish(ModelResult& res, const ModelParams& p, int L) {
  res.T_cd_over_N = 0.0;
  for (int h = 0; h < L; ++h) {
    res.T_cd[h] = 0.0;
    for (int j = 0; j < L; ++j) res.T_cd[h] += res.T_cd_pair[h * L + j];
    res.T_cd_over_N += res.T_cd[h];
  }
  res.T_over_N = res.T_cd_over_N + p.K * res.T_ca_over_N;
  return res;
}
}  // namespace

WallPairs parse_wall_pairs(const std::string& s, const std::string& field) {
  if (s == "layer") return WallPairs::depleted_layer;
  if (s == "product") return WallPairs::product;
  throw InputError(field, "must be layer or product (got '" + s + "')");
}

ModelResult evaluate_excluded_model(const Distribution& dist, const ModelParams& p,
                                    const std::vector<double>& sizes, const ExcludedOptions& opt,
                                    const std::optional<WallBox>& walls) {
  ModelResult res = evaluate_model(dist, p, sizes);  // validates; the random-centre counts
  if (p.d == 2 && dist.r_max() > kMaxDiscOmega * dist.r_min())
    throw InputError("omega", "size ratio too large for the 2D excluded-volume model (omega up to " +
                                  std::to_string(static_cast<int>(kMaxDiscOmega)) + ")");
  if (!(p.nu < 1.0)) throw InputError("nu", "must be < 1 for the excluded-volume model (got " + format_number(p.nu) + ")");
  if (opt.bins_per_level < 1 || opt.disc_bins_per_level < 1 || !(opt.k_max > 0) || !(opt.dk > 0) ||
      !(opt.disc_dr > 0) || !(opt.disc_range > 0))
    throw InputError("excluded", "bins per level >= 1, k_max, dk, disc_dr and disc_range > 0 required");
  const int L = static_cast<int>(sizes.size());
  const int d = p.d;
  const double vp = unit_ball_volume(d) * dist.moment(d, 0.0, dist.r_max());
  const double c = p.nu / vp;  // number density

  // Size classes: bins_per_level geometric slices of each level's radii.
  std::vector<Bin> bins;
  const int per_level = d == 2 ? opt.disc_bins_per_level : opt.bins_per_level;
  double lo = dist.r_min();
  for (int h = 0; h < L; ++h) {
    const double hi = std::min(0.5 * sizes[h], dist.r_max());
    if (hi > lo) {
      for (int q = 0; q < per_level; ++q) {
        const double a = lo * std::pow(hi / lo, double(q) / per_level);
        const double b = q + 1 == per_level ? hi : lo * std::pow(hi / lo, double(q + 1) / per_level);
        const double P = dist.moment(0, a, b);
        if (!(P > kMinBinProbability)) continue;
        const double size = d == 3 ? std::cbrt(dist.moment(3, a, b) / P) : std::sqrt(dist.moment(2, a, b) / P);
        bins.push_back({h, P, dist.moment(1, a, b) / P, 2.0 * size});
      }
      lo = hi;
    }
  }
  if (bins.empty()) {  // one radius (r_min = r_max): one class, on the level that holds it
    int h = 0;
    while (h + 1 < L && 0.5 * sizes[h] < dist.r_max()) ++h;
    bins.push_back({h, 1.0, dist.r_max(), 2.0 * dist.r_max()});
  }
  const int B = static_cast<int>(bins.size());
  std::vector<double> rho(B), sigma(B);
  for (int b = 0; b < B; ++b) rho[b] = c * bins[b].P, sigma[b] = bins[b].sigma;

  // Windows: every bin's own level and the levels it searches.
  std::vector<Window> win;
  double reach = 0.0;
  for (int a = 0; a < B; ++a) {
    const int h = bins[a].level;
    win.push_back({a, h, sizes[h], sizes[h], 0.5});
    for (int j = 0; j < L; ++j) {
      const bool searched = p.search == Search::top_down ? j < h : j > h;
      if (searched) win.push_back({a, j, bins[a].r_mean + 0.5 * sizes[j], sizes[j], 1.0});
    }
  }
  for (const Window& w : win) reach = std::max(reach, std::sqrt(3.0) * (w.c + w.s));
  if (d == 2) {
    std::vector<detail::WallProfile> prof;
    const std::vector<double> excess = disc_excess(bins, rho, sigma, win, p.nu, opt, walls ? &prof : nullptr);
    if (walls) {
      apply_walls(2, *walls, opt.wall_pairs, c, bins, prof, win, excess, sizes, res);
    } else {
      for (std::size_t w = 0; w < win.size(); ++w)
        res.T_cd_pair[bins[win[w].bin].level * L + win[w].level_searched] += win[w].half * bins[win[w].bin].P * excess[w];
    }
    return finish(res, p, L);
  }
  const detail::PyMixture py(rho, sigma);

  // Wave numbers k_m = m dk, m = 1..N-1, up to k_max.
  const double sigma_min = *std::min_element(sigma.begin(), sigma.end());
  const double kmax = opt.k_max / sigma_min;
  const std::size_t N = next_pow2(kmax / (opt.dk * std::numbers::pi / reach) + 1.0);
  if (N > static_cast<std::size_t>(kMaxWaveNumbers))
    throw InputError("omega", "size ratio too large for the excluded-volume model (needs " + std::to_string(N) +
                                  " wave numbers, at most " + std::to_string(kMaxWaveNumbers) +
                                  "; omega up to ~3000 is supported)");
  const double dk = kmax / static_cast<double>(N);

  // Y_{a,j}(k) = sum_{b in level j} rho_b hhat_ab(k), stored as k Y for the sine transform.
  std::vector<std::vector<double>> v(L, std::vector<double>(B, 0.0)), y;
  for (int b = 0; b < B; ++b) v[bins[b].level][b] = std::sqrt(rho[b]);
  std::vector<std::vector<double>> F(win.size(), std::vector<double>(N * kPad, 0.0));
  for (std::size_t m = 1; m < N; ++m) {
    const double k = m * dk;
    py.apply_h(k, v, y);
    for (std::size_t w = 0; w < win.size(); ++w) {
      const int a = win[w].bin;
      F[w][m] = k * y[win[w].level_searched][a] / std::sqrt(rho[a]);
    }
  }
  // h_{a,j}(r_n) = dk / (2 pi^2 r_n) sum_m k_m Y(k_m) sin(k_m r_n); excess = int h A_W dr.
  const std::size_t Nf = N * kPad;
  const double dr = std::numbers::pi / (static_cast<double>(Nf) * dk);
  std::vector<double> excess(win.size(), 0.0);  // per particle of the window's bin
  for (std::size_t w = 0; w < win.size(); ++w) {
    const Window& wi = win[w];
    detail::sine_transform(F[w]);
    const int nmax = static_cast<int>(std::min<double>(Nf - 1, std::ceil(std::sqrt(3.0) * (wi.c + wi.s) / dr)));
    const std::vector<double> A = detail::window_shell_areas(wi.c, wi.s, dr, nmax);
    double x = 0.0;
    for (int n = 1; n <= nmax; ++n) x += F[w][n] / (n * dr) * A[n];
    excess[w] = x * dk / (2.0 * std::numbers::pi * std::numbers::pi) * dr;
  }
  if (!walls) {
    for (std::size_t w = 0; w < win.size(); ++w)
      res.T_cd_pair[bins[win[w].bin].level * L + win[w].level_searched] += win[w].half * bins[win[w].bin].P * excess[w];
  } else {
    apply_walls(3, *walls, opt.wall_pairs, c, bins, wall_profiles(rho, sigma, bins, opt), win, excess, sizes, res);
  }
  return finish(res, p, L);
}

ExcludedSizes refine_sizes_excluded(const Distribution& dist, const ModelParams& p, std::vector<double> sizes,
                                    const ExcludedOptions& opt, const std::function<void(double, int, double)>& on_step) {
  ExcludedSizes out;
  out.model = evaluate_excluded_model(dist, p, sizes, opt);
  out.evaluations = 1;
  const int L = static_cast<int>(sizes.size());
  int stage = 0;
  for (double step : {1.25, 1.1}) {
    for (bool improved = true; improved;) {
      improved = false;
      for (int h = 0; h + 1 < L; ++h)
        for (double f : {1.0 / step, step}) {
          std::vector<double> trial = sizes;
          trial[h] *= f;
          if ((h > 0 && !(trial[h] > trial[h - 1])) || !(trial[h] < trial[h + 1])) continue;
          const ModelResult m = evaluate_excluded_model(dist, p, trial, opt);
          ++out.evaluations;
          if (m.T_over_N < out.model.T_over_N) {
            sizes = trial;
            out.model = m;
            improved = true;
          }
          if (on_step) on_step(std::min(0.99, 0.5 * (stage + (h + 1.0) / L)), out.evaluations, out.model.T_over_N);
        }
    }
    ++stage;
  }
  out.sizes = sizes;
  return out;
}

}  // namespace hgrid
