#include "hgridlab/advice/skin_tuner.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/model/distribution.hpp"

namespace hgrid {

SkinTuner::SkinTuner(int d, std::uint64_t builds_per_window) : d_(d), window_(builds_per_window) {
  if (d != 2 && d != 3) throw InputError("d", "must be 2 or 3");
  if (builds_per_window < 1) throw InputError("builds_per_window", "must be >= 1");
}

SkinMeasurement skin_measurement(double skin, const ContactListStats& now, const ContactListStats& before, double n) {
  const double steps = static_cast<double>(std::max<std::uint64_t>(1, now.steps - before.steps));
  const double builds = static_cast<double>(std::max<std::uint64_t>(1, now.builds - before.builds));
  const double grid = now.seconds_grid - before.seconds_grid;
  SkinMeasurement m;
  m.skin = skin;
  m.steps_per_build = steps / builds;
  if (now.travel_steps > before.travel_steps)
    m.travel_per_step = (now.travel - before.travel) / static_cast<double>(now.travel_steps - before.travel_steps);
  if (now.travel_one > before.travel_one)
    m.travel_growth = (now.travel_two - before.travel_two) / (now.travel_one - before.travel_one);
  m.contacts_per_n = static_cast<double>(now.contacts) / n;
  m.candidates_per_n = static_cast<double>(now.candidates_tested - before.candidates_tested) / steps / n;
  m.seconds_grid = grid / builds;
  m.seconds_store = (now.seconds_build - before.seconds_build - grid) / builds;
  m.seconds_test = (now.seconds_test - before.seconds_test) / steps;
  m.seconds_check = (now.seconds_check - before.seconds_check) / steps;
  return m;
}

double SkinTuner::first_skin(std::span<const double> radii) {
  if (radii.empty()) return 0;
  double mean = 0;
  for (const double r : radii) mean += r;
  return 0.2 * mean / static_cast<double>(radii.size());
}

std::optional<double> SkinTuner::after_build(const ContactListStats& s, double skin, std::span<const double> radii,
                                             double nu) {
  if (!(nu >= 0 && nu < 1)) throw InputError("nu", "must be in [0, 1)");
  if (!due(s) || radii.empty()) return std::nullopt;
  const SkinMeasurement m = skin_measurement(skin, s, last_, static_cast<double>(radii.size()));
  last_ = s;
  if (!(m.skin > 0)) return std::nullopt;
  // Two skins are needed: the first window's is doubled for the second;
  // later, this window beside the last one measured at a skin at least
  // kSkinRatio away (nearer skins would leave the model's slopes to noise).
  if (!other_) {
    other_ = m;
    return 2 * m.skin;
  }
  const Empirical dist(std::vector<double>(radii.begin(), radii.end()));
  predicted_ = choose_skin(*other_, m, dist, d_, std::min(nu, 0.95), 1e-3 * dist.r_min(), 4 * dist.r_max());
  if (std::max(other_->skin, m.skin) >= kSkinRatio * std::min(other_->skin, m.skin)) other_ = m;
  return predicted_->skin;
}

}  // namespace hgrid
