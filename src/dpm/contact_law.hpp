// Linear spring-dashpot normal force with a prescribed contact time and
// restitution (Luding, "Introduction to discrete element methods", 2008,
// Eqs. for the linear model): for reduced mass m, m x'' = -k x - g x' with
//   omega^2 = k/m - eta^2, eta = g / (2 m), t_c = pi / omega, e = exp(-eta t_c),
// so k = m (pi^2 + ln^2 e) / t_c^2 and g = -2 m ln(e) / t_c. Both scale with
// m, so every pair has the same t_c and e; the law stores k/m and g/m.
#pragma once
#include <cmath>
#include <numbers>

namespace hgrid::dpm {

struct SpringDashpot {
  double k_per_mass = 0;  // (pi^2 + ln^2 e) / t_c^2
  double g_per_mass = 0;  // -2 ln(e) / t_c

  static SpringDashpot from(double contact_time, double restitution) {
    const double le = std::log(restitution);
    return {(std::numbers::pi * std::numbers::pi + le * le) / (contact_time * contact_time),
            -2.0 * le / contact_time};
  }
  /// Normal force magnitude (positive = repulsive) at overlap delta and
  /// overlap rate delta_dot for reduced mass m.
  double force(double m, double delta, double delta_dot) const {
    return m * (k_per_mass * delta + g_per_mass * delta_dot);
  }
  /// Elastic energy stored at overlap delta.
  double energy(double m, double delta) const { return 0.5 * m * k_per_mass * delta * delta; }
};

}  // namespace hgrid::dpm
