// Validation of a DPM config and the one place a composition of effects is chosen.
#include "hgridlab/dpm/simulation.hpp"

#include <cmath>
#include <string>

#include "hgridlab/dpm/engine.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/base/threads.hpp"

namespace hgrid::dpm {

namespace {

bool positive(double x) { return std::isfinite(x) && x > 0; }

template <int D, Boundary B, bool F>
std::unique_ptr<Simulation> with_gravity(const DpmConfig& c, const Packing& p, const std::vector<double>& v) {
  if (c.gravity) return std::make_unique<Engine<D, B, F, true>>(c, p, v);
  return std::make_unique<Engine<D, B, F, false>>(c, p, v);
}
template <int D, Boundary B>
std::unique_ptr<Simulation> with_friction(const DpmConfig& c, const Packing& p, const std::vector<double>& v) {
  return c.friction ? with_gravity<D, B, true>(c, p, v) : with_gravity<D, B, false>(c, p, v);
}
template <int D>
std::unique_ptr<Simulation> with_boundary(const DpmConfig& c, const Packing& p, const std::vector<double>& v) {
  return c.boundary == Boundary::walls ? with_friction<D, Boundary::walls>(c, p, v)
                                       : with_friction<D, Boundary::periodic>(c, p, v);
}

}  // namespace

void validate(const DpmConfig& c) {
  if (c.d != 2 && c.d != 3) throw InputError("d", "must be 2 or 3");
  check_threads(c.threads);
  for (int k = 0; k < c.d; ++k)
    if (!positive(c.box[k])) throw InputError("box", "side lengths must be finite and > 0");
  if (!positive(c.contact_time)) throw InputError("contact_time", "must be finite and > 0");
  if (!(c.restitution > 0 && c.restitution <= 1)) throw InputError("restitution", "must be in (0, 1]");
  if (!positive(c.dt)) throw InputError("dt", "must be finite and > 0");
  if (c.dt > c.contact_time / kMinStepsPerContact * (1 + 1e-12))
    throw InputError("dt", "time step " + std::to_string(c.dt) + " is larger than contact_time / " +
                               std::to_string(static_cast<int>(kMinStepsPerContact)) + " = " +
                               std::to_string(c.contact_time / kMinStepsPerContact) +
                               "; a contact would not be resolved (use dt_over_tc <= " +
                               std::to_string(1.0 / kMinStepsPerContact) + ")");
  if (c.friction && !(std::isfinite(c.mu) && c.mu >= 0)) throw InputError("friction.mu", "must be finite and >= 0");
  if (c.friction && !(std::isfinite(c.friction_damping) && c.friction_damping >= 0))
    throw InputError("friction.damping", "must be finite and >= 0");
  for (int k = 0; k < c.d; ++k)
    if (!std::isfinite(c.g[k])) throw InputError("gravity", "components must be finite");
  if (!positive(c.density)) throw InputError("density", "must be finite and > 0");
  if (c.sizes.empty()) throw InputError("sizes", "at least one cell size is needed");
  if (!(std::isfinite(c.skin) && c.skin >= 0)) throw InputError("skin", "must be finite and >= 0");
  if (c.friction && c.tangential == TangentialLaw::spring && !positive(c.tangential_stiffness))
    throw InputError("tangential_stiffness", "must be finite and > 0");
}

std::unique_ptr<Simulation> make_simulation(const DpmConfig& c, const Packing& p, const std::vector<double>& v) {
  validate(c);
  if (p.d != c.d) throw InputError("d", "the initial state has d = " + std::to_string(p.d));
  if (p.boundary != c.boundary) throw InputError("boundary", "the initial state has another boundary");
  if (!v.empty() && v.size() != p.size() * static_cast<std::size_t>(c.d))
    throw InputError("velocities", "need N x d values");
  return c.d == 2 ? with_boundary<2>(c, p, v) : with_boundary<3>(c, p, v);
}

}  // namespace hgrid::dpm
