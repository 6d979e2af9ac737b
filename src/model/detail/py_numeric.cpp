// Numerical Percus-Yevick mixture (Lado's scheme with Anderson mixing); see py_numeric.hpp.
#include "hgridlab/model/detail/py_numeric.hpp"

#include <gsl/gsl_sf_bessel.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace hgrid::detail {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr int kHistory = 10;      // Anderson mixing depth
constexpr double kMixing = 0.5;   // fraction of the residual taken per step
constexpr double kRegularise = 1e-12;
constexpr double kStageTol = 1e-4;  // intermediate densities of the continuation: max |gamma_new - gamma|
constexpr int kStall = 60;  // iterations without a new smallest residual before a stage gives up
constexpr double kStage = 0.25;     // largest continuation step in t

// The radial kernel of the d-dimensional Fourier transform of a radial function.
double kernel(int d, double x) {
  if (d == 2) return gsl_sf_bessel_J0(x);
  return x < 1e-8 ? 1.0 - x * x / 6.0 : std::sin(x) / x;
}
// sum_m y_m k_m, in an order fixed at compile time (the same for any thread count).
double dot(const double* y, const double* k, int n) {
  double s = 0;
#pragma omp simd reduction(+ : s)
  for (int m = 0; m < n; ++m) s += y[m] * k[m];
  return s;
}
double measure(int d, double r) { return d == 2 ? 2.0 * kPi * r : 4.0 * kPi * r * r; }

// Solves A X = B for X (A, B: n x n, row-major) by Gaussian elimination with
// partial pivoting; A is destroyed and X is left in B.
void solve(std::vector<double>& a, std::vector<double>& b, int n, std::vector<int>& piv) {
  piv.resize(n);
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::fabs(a[r * n + c]) > std::fabs(a[p * n + c])) p = r;
    piv[c] = p;
    if (p != c) {
      for (int k = 0; k < n; ++k) std::swap(a[c * n + k], a[p * n + k]);
      for (int k = 0; k < n; ++k) std::swap(b[c * n + k], b[p * n + k]);
    }
    const double inv = 1.0 / a[c * n + c];
    for (int r = c + 1; r < n; ++r) {
      const double f = a[r * n + c] * inv;
      if (f == 0.0) continue;
      for (int k = c + 1; k < n; ++k) a[r * n + k] -= f * a[c * n + k];
      for (int k = 0; k < n; ++k) b[r * n + k] -= f * b[c * n + k];
    }
  }
  for (int c = n - 1; c >= 0; --c) {
    const double inv = 1.0 / a[c * n + c];
    for (int k = 0; k < n; ++k) {
      double s = b[c * n + k];
      for (int j = c + 1; j < n; ++j) s -= a[c * n + j] * b[j * n + k];
      b[c * n + k] = s * inv;
    }
  }
}

// Least squares min |f - sum_i theta_i dF_i| by the normal equations (small, regularised).
std::vector<double> anderson_weights(const std::vector<std::vector<double>>& dF, const std::vector<double>& f) {
  const int m = static_cast<int>(dF.size());
  std::vector<double> a(m * m), b(m);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j <= i; ++j) {
      double s = 0;
      for (std::size_t q = 0; q < f.size(); ++q) s += dF[i][q] * dF[j][q];
      a[i * m + j] = a[j * m + i] = s;
    }
    double s = 0;
    for (std::size_t q = 0; q < f.size(); ++q) s += dF[i][q] * f[q];
    b[i] = s;
  }
  double scale = 0;
  for (int i = 0; i < m; ++i) scale = std::max(scale, a[i * m + i]);
  for (int i = 0; i < m; ++i) a[i * m + i] += kRegularise * scale + 1e-300;
  std::vector<double> bb(m * m, 0.0);  // one right-hand side in the first column
  for (int i = 0; i < m; ++i) bb[i * m] = b[i];
  std::vector<int> piv;
  solve(a, bb, m, piv);
  std::vector<double> t(m);
  for (int i = 0; i < m; ++i) t[i] = bb[i * m];
  return t;
}
}  // namespace

PyNumeric::PyNumeric(int d, std::vector<double> rho, std::vector<double> sigma, const PyNumericGrid& g,
                     const std::function<void(double, int)>& progress)
    : rho_(std::move(rho)), g_(g), progress_(progress) {
  const int M = size();
  if (M == 0 || sigma.size() != rho_.size() || (d != 2 && d != 3)) throw std::invalid_argument("PyNumeric: arguments");
  if (!(g.dr > 0) || !(g.range > 0) || g.nk < 2) throw std::invalid_argument("PyNumeric: grid");
  double eta = 0;
  for (int i = 0; i < M; ++i) eta += (d == 2 ? kPi / 4 : kPi / 6) * rho_[i] * std::pow(sigma[i], d);
  if (!(eta < 1.0)) throw std::invalid_argument("PyNumeric: packing fraction >= 1");

  std::vector<double> k(g.nk);
  kw_.resize(g.nk);
  // Wave numbers of the Fourier-Bessel (d = 2) or Fourier-sine (d = 3) series
  // on [0, range]: the inverse transform is exact for functions that vanish
  // beyond range, so gamma's decay sets the error, not a quadrature rule.
  const double R = g.range;
  for (int m = 0; m < g.nk; ++m) {
    if (d == 2) {
      const double j = gsl_sf_bessel_zero_J0(m + 1), j1 = gsl_sf_bessel_J1(j);
      k[m] = j / R;
      kw_[m] = 1.0 / (kPi * R * R * j1 * j1);
    } else {
      k[m] = (m + 1) * kPi / R;
      kw_[m] = k[m] * k[m] * (kPi / R) / (2.0 * kPi * kPi);
    }
  }
  // Nodes of each pair: r = i dr (i = 0 .. n), then sigma_ab; trapezoid weights times the measure.
  const int P = pairs();
  offset_.resize(P + 1);
  nodes_.resize(P);
  fw_.resize(P);
  std::vector<double> sig_ab(P);
  int n_max = 0;
  std::size_t total = 0;
  for (int a = 0; a < M; ++a)
    for (int b = a; b < M; ++b) {
      const int p = pair(a, b);
      const double s = 0.5 * (sigma[a] + sigma[b]);
      sig_ab[p] = s;
      const int n = static_cast<int>(std::floor(s / g.dr));
      n_max = std::max(n_max, n);
      nodes_[p] = n + 2;
      offset_[p] = total;
      total += n + 2;
      auto& w = fw_[p];
      w.assign(n + 2, g.dr);
      const double tail = s - n * g.dr;  // last interval [n dr, sigma_ab]
      w[0] = 0.5 * g.dr;
      w[n] = (n > 0 ? 0.5 * g.dr : 0.0) + 0.5 * tail;
      w[n + 1] = 0.5 * tail;
      for (int i = 0; i <= n; ++i) w[i] *= measure(d, i * g.dr);
      w[n + 1] *= measure(d, s);
    }
  offset_[P] = total;
  // Multiply-adds of one iteration: the forward and inverse transforms
  // (2 nk per node), and the Ornstein-Zernike solve per wave number (~2 M^3).
  const double per_iteration = 2.0 * static_cast<double>(total) * g.nk + 2.0 * g.nk * std::pow(M, 3.0);
  int budget_iterations = g.max_iterations;
  if (g.max_work > 0) {
    const double affordable = std::floor(g.max_work / per_iteration);
    if (affordable < kPyMinIterations) throw PyWorkBudget(per_iteration, static_cast<int>(affordable), true);
    budget_iterations = static_cast<int>(std::min<double>(affordable, g.max_iterations));
    g_.max_iterations = budget_iterations;
  }
  uniform_rows_ = std::max(n_max + 1, static_cast<int>(std::floor(g.r_out / g.dr)) + 1);
  const std::size_t rows = static_cast<std::size_t>(uniform_rows_) + P;
  kernel_.resize(rows * g.nk);
  for (std::size_t row = 0; row < rows; ++row) {
    const double r = row < static_cast<std::size_t>(uniform_rows_) ? row * g.dr : sig_ab[row - uniform_rows_];
    double* kr = &kernel_[row * g.nk];
    for (int m = 0; m < g.nk; ++m) kr[m] = kernel(d, k[m] * r);
  }

  // Density continuation: the fixed point at a fraction t of the densities,
  // extrapolated linearly from the last two (a secant predictor), starts the
  // next t; a step halves when its iteration fails.
  std::vector<double> x(total, 0.0), x_last(total, 0.0);
  double t_done = 0.0, t_last = 0.0, step_t = kStage;
  int attempts = 0;
  while (t_done < 1.0) {
    const double t = std::min(1.0, t_done + step_t);
    std::vector<double> trial = x;
    if (t_done > 0.0) {
      const double e = (t - t_done) / (t_done - t_last);
      for (std::size_t q = 0; q < total; ++q) trial[q] += e * (x[q] - x_last[q]);
    }
    const bool ok = iterate(trial, t, t < 1.0 ? kStageTol : g.tol);
    if (ok) {
      x_last.swap(x);
      x.swap(trial);
      t_last = t_done;
      t_done = t;
      step_t = std::min(kStage, 1.5 * step_t);
    } else if (iterations_ >= g_.max_iterations && budget_iterations < g.max_iterations) {
      throw PyWorkBudget(per_iteration, budget_iterations, false);
    } else if ((step_t *= 0.5) < 1e-3 || ++attempts > 40 || iterations_ >= g_.max_iterations) {
      throw std::runtime_error("Percus-Yevick iteration did not converge (packing fraction " + std::to_string(eta) + ")");
    }
  }
  fourier(x);  // Gamma(k) of the solution, for gamma_sums
  gamma_.resize(P);
  for (int p = 0; p < P; ++p) gamma_[p].assign(x.begin() + offset_[p], x.begin() + offset_[p + 1]);
}

bool PyNumeric::iterate(std::vector<double>& x, double t, double tol) {
  scale_ = t;
  const std::size_t total = x.size();
  std::vector<double> gx(total), f(total), x_prev, f_prev;
  std::vector<std::vector<double>> dX, dF;
  double first = -1, best = HUGE_VAL;
  int best_it = 0;
  for (int it = 1; iterations_ < g_.max_iterations; ++it) {
    ++iterations_;
    step(x, gx);
    if (progress_) progress_(t, iterations_);
    double res = 0;
    for (std::size_t q = 0; q < total; ++q) {
      f[q] = gx[q] - x[q];
      res = std::max(res, std::fabs(f[q]));
    }
    if (!std::isfinite(res)) return false;
    if (first < 0) first = res;
    if (res < best) best = res, best_it = it;
    // Give up (the caller takes a smaller density step) when the residual
    // grows well past its start or stops improving.
    if (res > 10.0 * std::max(first, 1.0) || it - best_it > kStall) return false;
    if (res < tol) {
      x.swap(gx);
      return true;
    }
    if (!x_prev.empty()) {
      std::vector<double> ddx(total), ddf(total);
      for (std::size_t q = 0; q < total; ++q) ddx[q] = x[q] - x_prev[q], ddf[q] = f[q] - f_prev[q];
      dX.push_back(std::move(ddx));
      dF.push_back(std::move(ddf));
      if (static_cast<int>(dX.size()) > kHistory) dX.erase(dX.begin()), dF.erase(dF.begin());
    }
    x_prev = x;
    f_prev = f;
    const std::vector<double> th = dF.empty() ? std::vector<double>{} : anderson_weights(dF, f);
    for (std::size_t q = 0; q < total; ++q) {
      double v = x[q] + kMixing * f[q];
      for (std::size_t i = 0; i < th.size(); ++i) v -= th[i] * (dX[i][q] + kMixing * dF[i][q]);
      x[q] = v;
    }
  }
  return false;
}

void PyNumeric::fourier(const std::vector<double>& x) {
  const int M = size(), P = pairs(), nk = g_.nk;
  // C_ab(k) = sum_nodes w c(r) K(k r), c = -(1 + gamma) inside contact.
  C_.resize(P);
  G_.resize(P);
#pragma omp parallel for schedule(dynamic)
  for (int p = 0; p < P; ++p) {
    C_[p].assign(nk, 0.0);
    G_[p].resize(nk);
    double* cp = C_[p].data();
    const int n = nodes_[p];
    for (int i = 0; i < n; ++i) {
      const double c = -(1.0 + x[offset_[p] + i]) * fw_[p][i];
      const std::size_t row = i + 1 < n ? static_cast<std::size_t>(i) : static_cast<std::size_t>(uniform_rows_ + p);
      const double* kr = &kernel_[row * nk];
      for (int m = 0; m < nk; ++m) cp[m] += c * kr[m];
    }
  }
  // Ornstein-Zernike per k: (I - C R) Gamma = C R C, R = diag(rho).
  std::vector<double> A(M * M), B(M * M), Cm(M * M);
  std::vector<int> piv;
  for (int m = 0; m < nk; ++m) {
    for (int a = 0; a < M; ++a)
      for (int b = 0; b < M; ++b) Cm[a * M + b] = C_[pair(a, b)][m];
    for (int a = 0; a < M; ++a)
      for (int b = 0; b < M; ++b) {
        A[a * M + b] = (a == b ? 1.0 : 0.0) - Cm[a * M + b] * scale_ * rho_[b];
        double s = 0;
        for (int c = 0; c < M; ++c) s += Cm[a * M + c] * scale_ * rho_[c] * Cm[c * M + b];
        B[a * M + b] = s;
      }
    solve(A, B, M, piv);
    for (int a = 0; a < M; ++a)
      for (int b = a; b < M; ++b) G_[pair(a, b)][m] = 0.5 * (B[a * M + b] + B[b * M + a]);
  }
}

void PyNumeric::step(const std::vector<double>& x, std::vector<double>& out) {
  fourier(x);
  const int P = pairs(), nk = g_.nk;
#pragma omp parallel for schedule(dynamic)
  for (int p = 0; p < P; ++p) {
    std::vector<double> y(nk);
    for (int m = 0; m < nk; ++m) y[m] = G_[p][m] * kw_[m];
    const int n = nodes_[p];
    for (int i = 0; i < n; ++i) {
      const std::size_t row = i + 1 < n ? static_cast<std::size_t>(i) : static_cast<std::size_t>(uniform_rows_ + p);
      out[offset_[p] + i] = dot(y.data(), &kernel_[row * nk], nk);
    }
  }
}

std::vector<std::vector<double>> PyNumeric::gamma_sums(int a, const std::vector<std::vector<double>>& w,
                                                       int count) const {
  if (count > uniform_rows_) throw std::invalid_argument("PyNumeric::gamma_sums: beyond r_out");
  const int M = size(), nk = g_.nk;
  std::vector<std::vector<double>> out(w.size(), std::vector<double>(count, 0.0));
  std::vector<double> y(nk);
  for (std::size_t v = 0; v < w.size(); ++v) {
    std::fill(y.begin(), y.end(), 0.0);
    for (int b = 0; b < M; ++b)
      if (w[v][b] != 0.0)
        for (int m = 0; m < nk; ++m) y[m] += w[v][b] * G_[pair(a, b)][m];
    for (int m = 0; m < nk; ++m) y[m] *= kw_[m];
#pragma omp parallel for schedule(static)
    for (int n = 0; n < count; ++n) out[v][n] = dot(y.data(), &kernel_[static_cast<std::size_t>(n) * nk], nk);
  }
  return out;
}

}  // namespace hgrid::detail
