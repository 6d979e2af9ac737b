#include "hgridlab/advice/lammps_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "hgridlab/calibration/least_squares.hpp"
#include "hgridlab/base/error.hpp"

namespace hgrid {

LammpsFit fit_lammps(const std::vector<LammpsSample>& samples) {
  int packings = 0;
  for (const auto& s : samples) {
    if (s.packing < 0) throw InputError("packing", "training packings are numbered from 0");
    packings = std::max(packings, s.packing + 1);
  }
  constexpr std::size_t kShared = kLammpsTerms - 1;  // every term but `particles`
  if (samples.size() <= kShared + static_cast<std::size_t>(packings))
    throw InputError("samples", "more measured builds than the fit's " + std::to_string(kShared) +
                                    " coefficients and one constant per packing");
  std::vector<std::vector<double>> X;
  for (const auto& s : samples) {
    if (!(s.seconds > 0)) throw InputError("seconds", "every measured build must take > 0 s");
    const auto t = s.terms.as_array();
    std::vector<double> row(t.begin() + 1, t.end());
    row.resize(kShared + static_cast<std::size_t>(packings), 0.0);
    row[kShared + static_cast<std::size_t>(s.packing)] = 1.0;
    for (double& x : row) x /= s.seconds;  // relative residuals: the builds span decades
    X.push_back(row);
  }
  const detail::LinearFit f = detail::nonnegative_least_squares(X, std::vector<double>(samples.size(), 1.0));
  LammpsFit out;
  for (std::size_t k = 0; k < kShared; ++k) {
    out.coef.c[k + 1] = f.coef[k];
    out.stderr_[k + 1] = std::sqrt(std::max(0.0, f.cov[k][k]));
  }
  std::vector<double> n(static_cast<std::size_t>(packings), 0.0);
  for (const auto& s : samples) n[static_cast<std::size_t>(s.packing)] = s.terms.particles;
  for (int p = 0; p < packings; ++p)
    out.coef.c[0] += f.coef[kShared + static_cast<std::size_t>(p)] / n[static_cast<std::size_t>(p)] / packings;
  double sum2 = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    double predicted = 0;
    for (std::size_t k = 0; k < X[i].size(); ++k) predicted += X[i][k] * f.coef[k];
    sum2 += (predicted - 1) * (predicted - 1);
    out.max_rel = std::max(out.max_rel, std::abs(predicted - 1));
  }
  out.rms_rel = std::sqrt(sum2 / double(samples.size()));
  return out;
}

LammpsCoefficients lammps_coefficients(std::string* source) {
  const char* path = std::getenv("HGRID_LAMMPS_MODEL");
  if (!path || !*path) {
    if (source) *source = "default";
    return default_lammps_coefficients();
  }
  std::ifstream f(path);
  if (!f) throw InputError("HGRID_LAMMPS_MODEL", std::string("cannot read '") + path + "'");
  LammpsCoefficients c;
  try {
    const auto j = nlohmann::json::parse(f);
    const auto v = j.at("coefficients").get<std::vector<double>>();
    if (v.size() != static_cast<std::size_t>(kLammpsTerms)) throw std::runtime_error("size");
    for (std::size_t k = 0; k < v.size(); ++k) {
      if (!(std::isfinite(v[k]) && v[k] >= 0)) throw std::runtime_error("value");
      c.c[k] = v[k];
    }
  } catch (const std::exception&) {
    throw InputError("HGRID_LAMMPS_MODEL", std::string("'") + path + "' is not a fit.json of bench/lammps_model (" +
                                               std::to_string(kLammpsTerms) + " finite coefficients >= 0)");
  }
  if (source) *source = path;
  return c;
}

}  // namespace hgrid
