#include "hgridlab/scenes/dpm_scene_file.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "hgridlab/calibration/calibration.hpp"
#include "hgridlab/scenes/detail/scene_reader.hpp"

#include "hgridlab/base/error.hpp"
#include "hgridlab/base/threads.hpp"

namespace hgrid::dpm {
namespace {

const detail::SceneSections kSections = {
    {"initial", {"d", "n", "nu", "alpha", "omega", "boundary", "placement", "seed", "speed", "velocity_seed"}},
    {"contact", {"contact_time", "restitution", "dt_over_tc", "density"}},
    {"effects", {"friction", "mu", "friction_damping", "tangential", "tangential_stiffness", "gravity"}},
    {"run", {"steps", "sample_every", "threads", "skin"}},
    {"grids", {"method", "K", "reference_size"}},
};

using detail::check_keys;
using detail::count;
using detail::flag;
using detail::number;
using detail::section;
using detail::text;

}  // namespace

DpmScene load_dpm_scene(const std::string& path, const std::string& scale) {
  detail::check_scale_name(scale);
  toml::table root = detail::read_scene_file(path).root;
  std::set<std::string> top{"name", "description", "kind", "scale"};
  for (const auto& [name, keys] : kSections) top.insert(name);
  check_keys(root, "", top);
  // [scale.<scale>.<section>] keys replace the section's.
  for (const auto& [name, keys] : kSections) {
    check_keys(section(root, name), name + ".", keys);
    if (const auto* over = detail::scale_section(root, scale, name, kSections)) {
      if (!root.contains(name)) root.insert(name, toml::table{});
      auto* base = root[name].as_table();
      for (const auto& [k, v] : *over) base->insert_or_assign(k.str(), v);
    }
  }

  DpmScene s;
  s.source = path;
  s.scale = scale;
  s.name = text(root, "", "name", "");
  if (s.name.empty()) throw InputError("name", "a scene needs a name");
  s.description = text(root, "", "description", "");

  const auto& in = section(root, "initial");
  s.initial.d = static_cast<int>(count(in, "initial", "d", 2));
  s.initial.n = count(in, "initial", "n", 0);
  s.initial.nu = number(in, "initial", "nu", 0.4);
  s.initial.dist = "powerlaw";
  s.initial.alpha = number(in, "initial", "alpha", -3);
  s.initial.omega = number(in, "initial", "omega", 20);
  s.initial.boundary = parse_boundary(text(in, "initial", "boundary", "walls"));
  s.initial.placement = parse_placement(text(in, "initial", "placement", "excluded"));
  s.initial.seed = count(in, "initial", "seed", 1);
  s.speed = number(in, "initial", "speed", 1.0);
  s.velocity_seed = count(in, "initial", "velocity_seed", 1);
  if (s.initial.n < 2) throw InputError("initial.n", "need at least 2 particles");
  if (!(s.speed > 0)) throw InputError("initial.speed", "must be > 0");

  const auto& ct = section(root, "contact");
  auto& c = s.config;
  c.d = s.initial.d;
  c.boundary = s.initial.boundary;
  c.contact_time = number(ct, "contact", "contact_time", 1.0);
  c.restitution = number(ct, "contact", "restitution", 0.8);
  c.density = number(ct, "contact", "density", 1.0);
  s.dt_over_tc = number(ct, "contact", "dt_over_tc", 0.02);
  c.dt = s.dt_over_tc * c.contact_time;
  if (!(s.dt_over_tc > 0) || s.dt_over_tc > 1.0 / kMinStepsPerContact)
    throw InputError("contact.dt_over_tc", "must be in (0, 1/" + std::to_string(static_cast<int>(kMinStepsPerContact)) +
                                               "]: a contact needs at least " +
                                               std::to_string(static_cast<int>(kMinStepsPerContact)) + " steps");

  const auto& ef = section(root, "effects");
  c.friction = flag(ef, "effects", "friction", false);
  c.mu = number(ef, "effects", "mu", 0.5);
  c.friction_damping = number(ef, "effects", "friction_damping", 1.0);
  const std::string tangential = text(ef, "effects", "tangential", "viscous");
  if (tangential == "viscous") c.tangential = TangentialLaw::viscous;
  else if (tangential == "spring") c.tangential = TangentialLaw::spring;
  else throw InputError("effects.tangential", "must be 'viscous' or 'spring' (got '" + tangential + "')");
  c.tangential_stiffness = number(ef, "effects", "tangential_stiffness", 2.0 / 7.0);
  if (!(std::isfinite(c.tangential_stiffness) && c.tangential_stiffness > 0))
    throw InputError("effects.tangential_stiffness", "must be finite and > 0");
  if (const auto* g = ef.get("gravity")) {
    const auto* a = g->as_array();
    if (!a || static_cast<int>(a->size()) != c.d) throw InputError("effects.gravity", "must be an array of d numbers");
    for (int k = 0; k < c.d; ++k) {
      auto v = (*a)[k].value<double>();
      if (!v) throw InputError("effects.gravity", "must be an array of d numbers");
      c.g[k] = *v;
    }
    c.gravity = true;
  }

  const auto& rn = section(root, "run");
  s.steps = count(rn, "run", "steps", 0);
  s.sample_every = count(rn, "run", "sample_every", 100);
  if (s.steps == 0) throw InputError("run.steps", "must be >= 1");
  if (s.sample_every == 0) throw InputError("run.sample_every", "must be >= 1");
  // Threads of contact detection, forces and integration (0 = all cores);
  // the trajectory is the same for any number. Default 1: the time model's
  // predicted speed-up is for one core.
  const std::uint64_t threads = count(rn, "run", "threads", 1);
  s.config.threads = check_threads(static_cast<int>(std::min<std::uint64_t>(threads, kMaxThreads + 1)), "run.threads");

  // The pair skin of the scene's contact-list run (in units of r_min = 1;
  // 0: rebuilt every step); the trajectory is the same for any skin. 1.0:
  // the faster of 0.5 and 1.0 on the free-cooling scene (docs/record/PERFORMANCE.md).
  s.config.skin = number(rn, "run", "skin", 1.0);
  if (!(std::isfinite(s.config.skin) && s.config.skin >= 0)) throw InputError("run.skin", "must be finite and >= 0");

  const auto& gr = section(root, "grids");
  s.method = parse_cell_method(text(gr, "grids", "method", "optimal"), "grids.method");
  if (const auto* k = gr.get("K"); k && k->is_string()) {
    if (k->value<std::string>() != "auto") throw InputError("grids.K", "must be a number or \"auto\"");
    s.K = calibrated_K("grids.K");
  } else {
    s.K = number(gr, "grids", "K", 0.2);
  }
  s.reference_size = number(gr, "grids", "reference_size", 2 * s.initial.omega);
  if (!(s.reference_size >= 2 * s.initial.omega))
    throw InputError("grids.reference_size", "must be >= 2 omega (the largest diameter, r_min = 1)");
  return s;
}

}  // namespace hgrid::dpm
