#include "hgridlab/calibration/least_squares.hpp"

#include <cmath>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit.h>
#include <memory>
#include <stdexcept>
#include <string>

namespace hgrid::detail {
namespace {

template <class T, void (*Free)(T*)>
struct GslDeleter {
  void operator()(T* p) const { Free(p); }
};
using Matrix = std::unique_ptr<gsl_matrix, GslDeleter<gsl_matrix, gsl_matrix_free>>;
using Vector = std::unique_ptr<gsl_vector, GslDeleter<gsl_vector, gsl_vector_free>>;
using Workspace = std::unique_ptr<gsl_multifit_linear_workspace,
                                  GslDeleter<gsl_multifit_linear_workspace, gsl_multifit_linear_free>>;

}  // namespace

LinearFit least_squares(const std::vector<std::vector<double>>& X, const std::vector<double>& y) {
  const std::size_t n = X.size();
  if (n == 0 || y.size() != n) throw std::invalid_argument("least_squares: X and y need the same, non-zero length");
  const std::size_t p = X[0].size();
  if (p == 0 || n <= p)
    throw std::invalid_argument("least_squares: need more rows (" + std::to_string(n) + ") than coefficients (" +
                                std::to_string(p) + ")");
  std::vector<double> scale(p, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (X[i].size() != p) throw std::invalid_argument("least_squares: rows of different length");
    if (!std::isfinite(y[i])) throw std::invalid_argument("least_squares: non-finite y");
    for (std::size_t k = 0; k < p; ++k) {
      if (!std::isfinite(X[i][k])) throw std::invalid_argument("least_squares: non-finite X");
      scale[k] = std::max(scale[k], std::abs(X[i][k]));
    }
  }
  for (double& s : scale)
    if (s == 0) s = 1;  // an all-zero column: its coefficient is left at 0 by the SVD

  gsl_set_error_handler_off();
  Matrix A(gsl_matrix_alloc(n, p)), C(gsl_matrix_alloc(p, p));
  Vector b(gsl_vector_alloc(n)), c(gsl_vector_alloc(p));
  Workspace ws(gsl_multifit_linear_alloc(n, p));
  for (std::size_t i = 0; i < n; ++i) {
    gsl_vector_set(b.get(), i, y[i]);
    for (std::size_t k = 0; k < p; ++k) gsl_matrix_set(A.get(), i, k, X[i][k] / scale[k]);
  }
  double chi2 = 0;
  if (gsl_multifit_linear(A.get(), b.get(), c.get(), C.get(), &chi2, ws.get()) != GSL_SUCCESS)
    throw std::runtime_error("least_squares: GSL multifit failed");

  // Back to the unscaled coefficients: c_k = c'_k / scale_k.
  LinearFit f;
  f.chi2 = chi2;
  f.dof = static_cast<int>(n - p);
  f.coef.resize(p);
  f.cov.assign(p, std::vector<double>(p));
  for (std::size_t k = 0; k < p; ++k) {
    f.coef[k] = gsl_vector_get(c.get(), k) / scale[k];
    for (std::size_t l = 0; l < p; ++l) f.cov[k][l] = gsl_matrix_get(C.get(), k, l) / (scale[k] * scale[l]);
  }
  return f;
}

LinearFit nonnegative_least_squares(const std::vector<std::vector<double>>& X, const std::vector<double>& y) {
  const std::size_t p = X.empty() ? 0 : X[0].size();
  std::vector<std::size_t> active(p);
  for (std::size_t k = 0; k < p; ++k) active[k] = k;
  for (;;) {
    std::vector<std::vector<double>> Xa(X.size(), std::vector<double>(active.size()));
    for (std::size_t i = 0; i < X.size(); ++i)
      for (std::size_t k = 0; k < active.size(); ++k) Xa[i][k] = X[i].at(active[k]);
    const LinearFit fa = least_squares(Xa, y);
    std::size_t worst = active.size();
    for (std::size_t k = 0; k < active.size(); ++k)
      if (fa.coef[k] < 0 && (worst == active.size() || fa.coef[k] < fa.coef[worst])) worst = k;
    if (worst == active.size() || active.size() == 1) {
      LinearFit f;
      f.chi2 = fa.chi2;
      f.dof = fa.dof;
      f.coef.assign(p, 0.0);
      f.cov.assign(p, std::vector<double>(p, 0.0));
      for (std::size_t k = 0; k < active.size(); ++k) {
        f.coef[active[k]] = std::max(0.0, fa.coef[k]);
        for (std::size_t l = 0; l < active.size(); ++l) f.cov[active[k]][active[l]] = fa.cov[k][l];
      }
      return f;
    }
    active.erase(active.begin() + static_cast<std::ptrdiff_t>(worst));
  }
}

}  // namespace hgrid::detail
