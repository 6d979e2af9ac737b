// Percus-Yevick structure of a hard-sphere mixture in 3D, from Baxter's
// factorisation of the Ornstein-Zernike equation (R. J. Baxter, J. Chem.
// Phys. 52 (1970) 4559; the mixture solution of J. L. Lebowitz, Phys. Rev.
// 133 (1964) A895). docs/MODEL.md section 8.
#pragma once
#include <complex>
#include <vector>

namespace hgrid::detail {

class PyMixture {
 public:
  /// Components with number densities rho_i > 0 and diameters sigma_i > 0;
  /// the packing fraction xi_3 = (pi/6) sum rho_i sigma_i^3 must be < 1.
  PyMixture(std::vector<double> rho, std::vector<double> sigma);

  int size() const { return static_cast<int>(rho_.size()); }
  double packing_fraction() const { return xi_[3]; }
  /// g_ab at contact (Lebowitz's closed form): 1/(1 - xi_3) + 3 xi_2 D/(1 - xi_3)^2,
  /// D = sigma_a sigma_b / (sigma_a + sigma_b).
  double contact_value(int a, int b) const;

  /// For wave number k > 0 and right-hand sides v (each of length size()),
  /// returns y = H(k) v for every v, where H_ab(k) = sqrt(rho_a rho_b) hhat_ab(k)
  /// and hhat_ab is the 3D Fourier transform of the total correlation
  /// function h_ab(r) = g_ab(r) - 1. Uses I + H = (Q^T(-k) Q(k))^{-1}.
  void apply_h(double k, const std::vector<std::vector<double>>& v, std::vector<std::vector<double>>& y) const;

 private:
  void fill_q(double k, std::vector<std::complex<double>>& q) const;
  std::vector<double> rho_, sigma_, a_, b_;
  double xi_[4] = {0, 0, 0, 0};
};

}  // namespace hgrid::detail
