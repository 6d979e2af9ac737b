// Percus-Yevick structure of a hard-sphere (d = 3) or hard-disc (d = 2)
// mixture, solved numerically: the Ornstein-Zernike equation in Fourier space
// (radial transforms by quadrature) with the closure c_ab = -(1 + gamma_ab)
// inside contact and c_ab = 0 outside, iterated to a fixed point of
// gamma = h - c (Lado's scheme: F. Lado, J. Chem. Phys. 49 (1968) 3092 and
// J. Comput. Phys. 8 (1971) 417), accelerated by Anderson mixing
// (D. G. Anderson, J. ACM 12 (1965) 547).
// Discs have no closed-form Percus-Yevick solution; in 3D this solver is
// checked against Baxter's (PyMixture). docs/MODEL.md section 8.
#pragma once
#include <functional>
#include <stdexcept>
#include <vector>

namespace hgrid::detail {

struct PyNumericGrid {
  double dr = 0;          // r step of the quadratures (and of gamma_sums' output)
  double range = 0;       // transforms are series on [0, range]: k_m = j_{0,m} / range (2D), m pi / range (3D)
  int nk = 0;             // number of wave numbers (the largest is about nk pi / range)
  double r_out = 0;       // gamma_sums covers r = 0 .. r_out
  double tol = 1e-6;      // converged when max |gamma_new - gamma| < tol (T/N moves < 1e-8 below 1e-5)
  int max_iterations = 1000;  // in all, over the density continuation
  /// If > 0: the most multiply-adds the iteration may take in all (one
  /// iteration's, known before the first: PyWorkBudget::work_per_iteration).
  double max_work = 0;
};

/// Thrown when the solution would need more than PyNumericGrid::max_work:
/// before any iteration when the budget buys fewer than kPyMinIterations
/// (the fewest a density continuation has taken), else when it runs out.
struct PyWorkBudget : std::runtime_error {
  PyWorkBudget(double per_iteration, int iterations, bool before)
      : std::runtime_error("Percus-Yevick iteration: work budget"),
        work_per_iteration(per_iteration), affordable_iterations(iterations), refused_before(before) {}
  double work_per_iteration;
  int affordable_iterations;
  bool refused_before;
};
inline constexpr int kPyMinIterations = 40;

class PyNumeric {
 public:
  /// Components with number densities rho_i > 0 and diameters sigma_i > 0;
  /// the packing fraction (unit-ball volume x sum rho_i (sigma_i / 2)^d) must
  /// be < 1. Solves at construction; throws std::runtime_error when the
  /// iteration does not converge.
  /// progress(t, iterations): after each iteration, t the density fraction being solved.
  /// With g.max_work > 0, throws PyWorkBudget (before the transforms' tables
  /// are built when the budget is too small to try).
  PyNumeric(int d, std::vector<double> rho, std::vector<double> sigma, const PyNumericGrid& g,
            const std::function<void(double, int)>& progress = {});

  int size() const { return static_cast<int>(rho_.size()); }
  int iterations() const { return iterations_; }
  double dr() const { return g_.dr; }

  /// gamma_ab at r = n dr for n = 0 .. floor(sigma_ab / dr), then at r = sigma_ab (last entry).
  const std::vector<double>& gamma_inside(int a, int b) const { return gamma_[pair(a, b)]; }
  /// g_ab at contact: 1 + gamma_ab(sigma_ab).
  double contact_value(int a, int b) const { return 1.0 + gamma_[pair(a, b)].back(); }

  /// For each weight vector w (length size()): sum_b w_b gamma_ab(n dr),
  /// n = 0 .. count - 1 (count <= r_out / dr + 1), by the inverse transform of
  /// sum_b w_b Gamma_ab(k).
  std::vector<std::vector<double>> gamma_sums(int a, const std::vector<std::vector<double>>& w, int count) const;

 private:
  int pair(int a, int b) const { return a <= b ? a * size() - a * (a - 1) / 2 + (b - a) : pair(b, a); }
  int pairs() const { return size() * (size() + 1) / 2; }
  // One Picard step: gamma (flat, all pairs) -> Gamma(k) (per pair) -> new gamma.
  void step(const std::vector<double>& x, std::vector<double>& out);
  void fourier(const std::vector<double>& x);  // fills G_ from gamma x
  bool iterate(std::vector<double>& x, double t, double tol);  // fixed point at densities t rho, from x

  std::vector<double> rho_;
  PyNumericGrid g_;
  std::vector<double> kw_;                     // inverse-transform weights of the wave numbers
  std::vector<double> kernel_;                 // K(k_m r) row-major: row (an r), then m
  int uniform_rows_ = 0;                       // rows 0 .. uniform_rows_ - 1: r = i dr; then one per pair: sigma_ab
  std::vector<std::size_t> offset_;            // per pair: start in the flat gamma vector
  std::vector<int> nodes_;                     // per pair: number of nodes (last = sigma_ab)
  std::vector<std::vector<double>> fw_;        // per pair: forward weights (quadrature x measure)
  std::vector<std::vector<double>> gamma_;     // per pair, at convergence
  std::vector<std::vector<double>> C_, G_;     // per pair: C_ab(k_m), Gamma_ab(k_m) (kept between iterations)
  std::function<void(double, int)> progress_;
  int iterations_ = 0;
  double scale_ = 1.0;                         // densities in use: scale_ x rho
};

}  // namespace hgrid::detail
