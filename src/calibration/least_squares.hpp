// Ordinary least squares with the parameters' covariance (GSL multifit).
#pragma once
#include <vector>

namespace hgrid::detail {

struct LinearFit {
  std::vector<double> coef;              // p fitted coefficients
  std::vector<std::vector<double>> cov;  // p x p covariance, scaled by the residual variance
  double chi2 = 0;                       // sum of squared residuals
  int dof = 0;                           // rows - p
};

/// Least squares for y ~ X c, X given row by row (n rows of p entries, n > p).
/// The covariance is s^2 (X^T X)^-1 with s^2 = chi2 / (n - p), so the
/// standard errors are sqrt(cov[i][i]). Columns are scaled to unit maximum
/// before the SVD solve, so coefficients of very different magnitude are fine.
/// Throws std::invalid_argument for n <= p, ragged rows or non-finite input.
LinearFit least_squares(const std::vector<std::vector<double>>& X, const std::vector<double>& y);

/// The same with every coefficient >= 0 (costs cannot be negative): fits,
/// then drops the column of the most negative coefficient and fits again
/// until none is negative (an active-set method that only removes). A
/// dropped column's coefficient, and its row and column of the covariance,
/// are 0. Needs more rows than columns left.
LinearFit nonnegative_least_squares(const std::vector<std::vector<double>>& X, const std::vector<double>& y);

}  // namespace hgrid::detail
