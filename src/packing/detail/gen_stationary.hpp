// When an equilibration is done: a stationarity test on the series of an
// observable sampled at equal intervals of Monte Carlo sweeps.
//
// Relaxation in these packings slows down as the run goes on (the counts
// move about as much from 100 to 200 sweeps as from 500 to 1000), so the
// test measures the drift per doubling of the run: a straight line fitted
// to the samples of the second half of the run, (s/2, s] after s sweeps,
// against ln(sweeps); its slope times ln 2 is the change of the observable
// from s/2 to s. The run is stationary when that drift, widened by two of
// its standard errors, is within a tolerance (kStationaryRelTol, 0.1 %) of the mean: noise
// cannot hide a drift, it only makes the run longer (a small packing, whose
// T/N is noisy, runs to its cap, which costs little). A drift below the
// tolerance per doubling moves the observable by at most that much again
// for every further doubling. The comparison of a chain's late part with an earlier one is
// Geweke's diagnostic (Geweke, in Bayesian Statistics 4, Oxford University
// Press, 1992); here on a logarithmic clock.
#pragma once
#include <cstddef>
#include <span>
#include <string>

namespace hgrid::detail {

/// Sweeps between two samples of the observable.
inline constexpr int kStationarySampleSweeps = 2;
/// Fewest samples before the test may pass.
inline constexpr std::size_t kStationaryMinSamples = 100;
/// Largest lag-1 autocorrelation of the residuals taken into the standard
/// error (a series that smooth is a drift the line does not follow).
inline constexpr double kStationaryMaxRho = 0.95;

struct Stationarity {
  bool stationary = false;
  double mean = 0;          // of the second half's samples
  double drift = 0;         // fitted change from s/2 to s
  double se = 0;            // its standard error (widened for the samples' correlation)
  std::size_t samples = 0;  // in the second half
};

/// The test on series[0..n), sample k taken after (k + 1) kStationarySampleSweeps
/// sweeps; not stationary while n < kStationaryMinSamples.
Stationarity test_stationary(std::span<const double> series, double rel_tol);

/// The test's parameters, for a packing's identity (a change of them is
/// another packing).
std::string stationarity_rule(double rel_tol);

}  // namespace hgrid::detail
