// Percus-Yevick mixture structure (Baxter's Q function); see py_mixture.hpp.
#include "hgridlab/model/detail/py_mixture.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace hgrid::detail {

namespace {
using cplx = std::complex<double>;

// In-place LU with partial pivoting of the n x n row-major matrix a.
void lu_decompose(std::vector<cplx>& a, std::vector<int>& piv, int n) {
  piv.resize(n);
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(a[r * n + c]) > std::abs(a[p * n + c])) p = r;
    piv[c] = p;
    if (p != c)
      for (int k = 0; k < n; ++k) std::swap(a[c * n + k], a[p * n + k]);
    const cplx inv = 1.0 / a[c * n + c];
    for (int r = c + 1; r < n; ++r) {
      const cplx f = a[r * n + c] * inv;
      a[r * n + c] = f;
      if (f == cplx(0.0)) continue;
      for (int k = c + 1; k < n; ++k) a[r * n + k] -= f * a[c * n + k];
    }
  }
}
}  // namespace

PyMixture::PyMixture(std::vector<double> rho, std::vector<double> sigma)
    : rho_(std::move(rho)), sigma_(std::move(sigma)) {
  if (rho_.size() != sigma_.size() || rho_.empty()) throw std::invalid_argument("PyMixture: sizes");
  const double c = std::numbers::pi / 6.0;
  for (int n = 0; n < 4; ++n)
    for (std::size_t i = 0; i < rho_.size(); ++i) xi_[n] += c * rho_[i] * std::pow(sigma_[i], n);
  if (!(xi_[3] < 1.0)) throw std::invalid_argument("PyMixture: packing fraction >= 1");
  const double e = 1.0 - xi_[3];
  a_.resize(rho_.size());
  b_.resize(rho_.size());
  for (std::size_t i = 0; i < rho_.size(); ++i) {
    a_[i] = (e + 3.0 * sigma_[i] * xi_[2]) / (e * e);
    b_[i] = -1.5 * sigma_[i] * sigma_[i] * xi_[2] / (e * e);
  }
}

double PyMixture::contact_value(int a, int b) const {
  const double e = 1.0 - xi_[3], D = sigma_[a] * sigma_[b] / (sigma_[a] + sigma_[b]);
  return 1.0 / e + 3.0 * xi_[2] * D / (e * e);
}

// J_m = int_0^L t^m e^{ikt} dt, m = 0, 1, 2: the closed form for |kL| >= 1, a
// power series below (the closed form cancels catastrophically as kL -> 0).
static void moments(double k, double L, cplx e, cplx J[3]) {  // e = exp(i k L)
  const double x = k * L;
  if (std::fabs(x) >= 1.0) {
    // z / (i k) = (Im z / k, -Re z / k): the quotient libgcc's complex
    // division returns for finite z (its ratio c / d is 0 here), without
    // the call.
    const auto over_ik = [k](cplx z) { return cplx(z.imag() / k, -z.real() / k); };
    J[0] = over_ik(e - 1.0);
    J[1] = over_ik(L * e - J[0]);
    J[2] = over_ik(L * L * e - 2.0 * J[1]);
    return;
  }
  // J_m = L^{m+1} sum_n (i x)^n / (n! (m + n + 1)); |x| < 1: stop once a term is below 1e-18.
  cplx term(1.0, 0.0);
  J[0] = J[1] = J[2] = cplx(0.0);
  for (int n = 0; n < 30 && std::abs(term) > 1e-18; ++n) {
    for (int m = 0; m < 3; ++m) J[m] += term / double(m + n + 1);
    term *= cplx(0.0, x) / double(n + 1);
  }
  J[0] *= L;
  J[1] *= L * L;
  J[2] *= L * L * L;
}

// Q_ij(k) = delta_ij - 2 pi sqrt(rho_i rho_j) int_{S_ij}^{R_ij} Q_ij(r) e^{ikr} dr with
// Q_ij(r) = a_i (r^2 - R_ij^2)/2 + b_i (r - R_ij), R_ij = (s_i + s_j)/2, S_ij = (s_i - s_j)/2.
// With r = S_ij + t, t in [0, L = s_j]: Q = c2 t^2 + c1 t + c0.
void PyMixture::fill_q(double k, std::vector<cplx>& q) const {
  const int n = size();
  q.assign(static_cast<std::size_t>(n) * n, cplx(0.0));
  thread_local std::vector<cplx> half, full;  // exp(i k sigma/2), exp(i k sigma)
  half.resize(n);
  full.resize(n);
  for (int i = 0; i < n; ++i) {
    half[i] = std::exp(cplx(0.0, 0.5 * k * sigma_[i]));
    full[i] = half[i] * half[i];
  }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double R = 0.5 * (sigma_[i] + sigma_[j]), L = sigma_[j];
      const double g = a_[i] * R + b_[i];
      const double c2 = 0.5 * a_[i], c1 = g - a_[i] * L, c0 = 0.5 * a_[i] * L * L - g * L;
      cplx J[3];
      moments(k, L, full[j], J);
      const cplx phase = half[i] * std::conj(half[j]);  // exp(i k S_ij)
      const cplx integral = phase * (c0 * J[0] + c1 * J[1] + c2 * J[2]);
      q[i * n + j] = (i == j ? 1.0 : 0.0) - 2.0 * std::numbers::pi * std::sqrt(rho_[i] * rho_[j]) * integral;
    }
}

void PyMixture::apply_h(double k, const std::vector<std::vector<double>>& v,
                        std::vector<std::vector<double>>& y) const {
  const int n = size();
  thread_local std::vector<cplx> q, z;
  thread_local std::vector<int> piv;
  fill_q(k, q);
  lu_decompose(q, piv, n);  // P Q = L U, L unit lower
  y.resize(v.size());
  z.resize(n);
  for (std::size_t c = 0; c < v.size(); ++c) {
    // Solve Q^H Q x = v: Q^H = U^H L^H P, so U^H w = v, L^H u = w, z = P^T u; then Q x = z.
    for (int i = 0; i < n; ++i) z[i] = v[c][i];
    for (int i = 0; i < n; ++i) {  // U^H lower triangular
      cplx s = z[i];
      for (int k2 = 0; k2 < i; ++k2) s -= std::conj(q[k2 * n + i]) * z[k2];
      z[i] = s / std::conj(q[i * n + i]);
    }
    for (int i = n - 1; i >= 0; --i) {  // L^H upper unit triangular
      cplx s = z[i];
      for (int k2 = i + 1; k2 < n; ++k2) s -= std::conj(q[k2 * n + i]) * z[k2];
      z[i] = s;
    }
    for (int i = n - 1; i >= 0; --i) std::swap(z[i], z[piv[i]]);  // z = P^T u
    for (int i = 0; i < n; ++i) std::swap(z[i], z[piv[i]]);       // apply P for Q x = z: P Q x = P z
    for (int i = 0; i < n; ++i) {                                  // L forward
      cplx s = z[i];
      for (int k2 = 0; k2 < i; ++k2) s -= q[i * n + k2] * z[k2];
      z[i] = s;
    }
    for (int i = n - 1; i >= 0; --i) {  // U backward
      cplx s = z[i];
      for (int k2 = i + 1; k2 < n; ++k2) s -= q[i * n + k2] * z[k2];
      z[i] = s / q[i * n + i];
    }
    y[c].resize(n);
    for (int i = 0; i < n; ++i) y[c][i] = z[i].real() - v[c][i];  // (I + H) v - v
  }
}

}  // namespace hgrid::detail
