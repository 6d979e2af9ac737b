#include "experiment/dpm_scene_file.hpp"

#include <map>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "experiment/calibration.hpp"
#include "experiment/detail/toml_keys.hpp"

#include "grid/error.hpp"

namespace hgrid::dpm {
namespace {

const std::set<std::string> kSections = {"initial", "contact", "effects", "run", "grids"};
const std::map<std::string, std::set<std::string>> kKeys = {
    {"initial", {"d", "n", "nu", "alpha", "omega", "boundary", "placement", "seed", "speed", "velocity_seed"}},
    {"contact", {"contact_time", "restitution", "dt_over_tc", "density"}},
    {"effects", {"friction", "mu", "friction_damping", "gravity"}},
    {"run", {"steps", "sample_every"}},
    {"grids", {"method", "K", "reference_size"}},
};

using detail::check_keys;

const toml::table& section(const toml::table& root, const std::string& name) {
  static const toml::table empty;
  const auto* t = root[name].as_table();
  if (root.contains(name) && !t) throw InputError(name, "must be a table");
  return t ? *t : empty;
}

double number(const toml::table& t, const std::string& sec, const std::string& key, double def) {
  const auto* n = t.get(key);
  if (!n) return def;
  if (auto v = n->value<double>()) return *v;
  throw InputError(sec + "." + key, "must be a number");
}
std::uint64_t count(const toml::table& t, const std::string& sec, const std::string& key, std::uint64_t def) {
  const auto* n = t.get(key);
  if (!n) return def;
  auto v = n->value<std::int64_t>();
  if (!v || *v < 0) throw InputError(sec + "." + key, "must be an integer >= 0");
  return static_cast<std::uint64_t>(*v);
}
std::string text(const toml::table& t, const std::string& sec, const std::string& key, const std::string& def) {
  const auto* n = t.get(key);
  if (!n) return def;
  if (auto v = n->value<std::string>()) return *v;
  throw InputError(sec + "." + key, "must be a string");
}
bool flag(const toml::table& t, const std::string& sec, const std::string& key, bool def) {
  const auto* n = t.get(key);
  if (!n) return def;
  if (auto v = n->value<bool>()) return *v;
  throw InputError(sec + "." + key, "must be true or false");
}

}  // namespace

DpmScene load_dpm_scene(const std::string& path, const std::string& scale) {
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << e.description() << " (line " << e.source().begin.line << ")";
    throw InputError(path, msg.str());
  }
  if (scale != "smoke" && scale != "default" && scale != "paper")
    throw InputError("--scale", "must be smoke, default or paper");
  std::set<std::string> top = kSections;
  top.insert({"name", "description", "kind", "scale"});
  check_keys(root, "", top);
  for (const auto& s : kSections) check_keys(section(root, s), s + ".", kKeys.at(s));
  // Scale overrides: [scale.<scale>.<section>] keys replace the section's.
  if (const auto* scales = root["scale"].as_table()) {
    check_keys(*scales, "scale.", {"smoke", "default", "paper"});
    for (const auto& [sk, sv] : *scales) {
      const auto* st = sv.as_table();
      if (!st) throw InputError("scale." + std::string(sk.str()), "must be a table");
      check_keys(*st, "scale." + std::string(sk.str()) + ".", kSections);
      for (const auto& [name, sub] : *st) {
        const auto* subt = sub.as_table();
        const std::string where = "scale." + std::string(sk.str()) + "." + std::string(name.str());
        if (!subt) throw InputError(where, "must be a table");
        check_keys(*subt, where + ".", kKeys.at(std::string(name.str())));
      }
    }
    if (const auto* st = (*scales)[scale].as_table())
      for (const auto& [name, sub] : *st) {
        if (!root.contains(name.str())) root.insert(name.str(), toml::table{});
        auto* base = root[name.str()].as_table();
        for (const auto& [k, v] : *sub.as_table()) base->insert_or_assign(k.str(), v);
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
