#include "hgridlab/scenes/scene.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <fstream>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>
#include <toml++/toml.h>

#include "hgridlab/calibration/calibration.hpp"
#include "hgridlab/packing/identity.hpp"
#include "hgridlab/scenes/detail/scene_reader.hpp"

#include "hgridlab/base/error.hpp"

namespace hgrid {
namespace {

using detail::check_keys;
using detail::numbers;
using detail::strings;

/// packings.n: at most the grid's particle index range (2^31 - 1).
constexpr std::int64_t kMaxSceneParticles = (std::int64_t{1} << 31) - 1;

const detail::SceneSections kSections = {
    {"packings", {"d", "n", "nu", "alpha", "omega", "sigma", "dist", "boundary", "placement", "method", "seeds",
                  "equilibrate", "sweeps", "stop", "stationary_tol", "moves"}}};

/// The packing lists of a scene, before expansion.
struct PackingLists {
  std::vector<std::int64_t> d{3}, n, seeds{1};
  std::vector<double> nu, alpha{-3}, omega{100}, sigma{0.5};
  std::vector<std::string> dist{"powerlaw"}, boundary{"periodic"}, placement{"random"};
  bool equilibrate = false;
  std::int64_t sweeps = kDefaultEquilibrationSweeps;
  bool sweeps_given = false;
  EquilibrationStop stop = EquilibrationStop::sweeps;
  bool stop_given = false;
  EquilibrationMoves moves = EquilibrationMoves::metropolis;
  bool moves_given = false;
  double stationary_tol = kStationaryRelTol;
  bool stationary_tol_given = false;
  ExcludedMethod method = ExcludedMethod::automatic;
  bool method_given = false;
};

/// The keys of t (a [packings] table, a group of it or a scale's override)
/// into p; `groups`: the table may hold [[packings.groups]] (read apart).
void read_packings(const toml::table& t, PackingLists& p, const std::string& where, bool groups = false) {
  auto keys = kSections.at("packings");
  if (groups) keys.insert("groups");
  check_keys(t, where, keys);
  for (const auto& [k, v] : t) {
    const std::string key(k.str());
    const std::string name = where + key;
    if (key == "d") p.d = detail::whole_numbers(v, name, 2, 3);
    else if (key == "n") p.n = detail::whole_numbers(v, name, 1, kMaxSceneParticles);
    else if (key == "nu") p.nu = numbers(v, name);
    else if (key == "alpha") p.alpha = numbers(v, name);
    else if (key == "omega") p.omega = numbers(v, name);
    else if (key == "sigma") p.sigma = numbers(v, name);
    else if (key == "seeds") p.seeds = detail::whole_numbers(v, name, 0, std::numeric_limits<std::int64_t>::max());
    else if (key == "dist") p.dist = strings(v, name);
    else if (key == "boundary") p.boundary = strings(v, name);
    else if (key == "placement") p.placement = strings(v, name);
    else if (key == "method") {
      p.method = parse_excluded_method(detail::one_string(v, name), name);
      p.method_given = true;
    } else if (key == "equilibrate") {
      auto b = v.value<bool>();
      if (!b) throw InputError(name, "must be true or false");
      p.equilibrate = *b;
    } else if (key == "stationary_tol") {
      const auto x = v.value<double>();
      if (!x || !(*x > 0 && *x <= 0.1)) throw InputError(name, "must be a number in (0, 0.1]");
      p.stationary_tol = *x;
      p.stationary_tol_given = true;
    } else if (key == "moves") {
      p.moves = parse_equilibration_moves(detail::one_string(v, name), name);
      p.moves_given = true;
    } else if (key == "stop") {
      p.stop = parse_equilibration_stop(detail::one_string(v, name), name);
      p.stop_given = true;
    } else if (key == "sweeps") {
      auto i = v.value<std::int64_t>();
      if (!i || *i < 1 || *i > kMaxEquilibrationSweeps)
        throw InputError(name, "must be an integer in [1, " + std::to_string(kMaxEquilibrationSweeps) + "]");
      p.sweeps = *i;
      p.sweeps_given = true;
    }
  }
}

void check_lists(const PackingLists& p) {
  if (p.n.empty()) throw InputError("packings.n", "is required (number of particles, >= 1)");
  if (p.sweeps_given && !p.equilibrate) throw InputError("packings.sweeps", "only applies with equilibrate = true");
  if (p.stop_given && !p.equilibrate) throw InputError("packings.stop", "only applies with equilibrate = true");
  if (p.moves_given && !p.equilibrate) throw InputError("packings.moves", "only applies with equilibrate = true");
  if (p.stationary_tol_given && p.stop != EquilibrationStop::stationary)
    throw InputError("packings.stationary_tol", "only applies with stop = \"stationary\"");
  if (p.nu.empty()) throw InputError("packings.nu", "is required (packing fraction, > 0)");
  for (double nu : p.nu)
    if (!(nu > 0 && nu < 1)) throw InputError("packings.nu", "must be in (0, 1)");
  for (double w : p.omega)
    if (!(w >= 1)) throw InputError("packings.omega", "must be >= 1");
  for (double s : p.sigma)
    if (!(s > 0)) throw InputError("packings.sigma", "must be > 0");
  for (const auto& s : p.dist)
    if (s != "powerlaw" && s != "lognormal") throw InputError("packings.dist", "must be 'powerlaw' or 'lognormal'");
  for (const auto& s : p.boundary) parse_boundary(s, "packings.boundary");
  bool excluded = false;
  for (const auto& s : p.placement) {
    const Placement pl = parse_placement(s, "packings.placement");
    if (pl == Placement::bed)
      throw InputError("packings.placement", "must be 'random' or 'excluded' in a scene (a bed is made by `hgrid generate --placement bed` and read as a file)");
    excluded |= pl == Placement::excluded;
  }
  if (p.method_given && !excluded) throw InputError("packings.method", "only applies to placement = \"excluded\"");
  if (p.equilibrate && !excluded)
    throw InputError("packings.equilibrate", "only applies to placement = \"excluded\"");
}

void read_grid(const toml::table& t, SceneGrid& g) {
  check_keys(t, "grid.", {"cells", "levels", "q", "K", "search"});
  if (auto v = t["cells"]) {
    g.cells = parse_cell_method(detail::one_string(*v.node(), "grid.cells"), "grid.cells");
  }
  if (auto v = t["levels"]) {
    if (v.is_array()) throw InputError("grid.levels", "takes one number, not a list");
    g.levels = static_cast<int>(detail::whole_numbers(*v.node(), "grid.levels", 1, 200).front());
  }
  if (auto v = t["q"]) {
    g.q = detail::one_number(*v.node(), "grid.q");
    if (!(g.q > 0)) throw InputError("grid.q", "must be > 0");
  }
  if (auto v = t["K"]) {
    if (auto text = v.value<std::string>()) {
      if (*text != "auto") throw InputError("grid.K", "must be a number >= 0 or \"auto\" (got \"" + *text + "\")");
      g.K = calibrated_K("grid.K");
    } else {
      g.K = detail::one_number(*v.node(), "grid.K");
      if (!(g.K >= 0)) throw InputError("grid.K", "must be >= 0");
    }
  }
  if (auto v = t["search"]) {
    g.searches.clear();
    for (const auto& s : strings(*v.node(), "grid.search")) g.searches.push_back(parse_search(s, "grid.search"));
  }
}

void read_record(const toml::table& t, SceneRecord& r) {
  check_keys(t, "record.", {"model", "occupancy"});
  for (const auto& [k, v] : t) {
    auto b = v.value<bool>();
    if (!b) throw InputError("record." + std::string(k.str()), "must be true or false");
    (k.str() == "model" ? r.model : r.occupancy) = *b;
  }
}

}  // namespace

std::string describe_point(const Scene& scene, std::size_t i) {
  const PackingSpec& p = scene.points.at(i).packing;
  std::ostringstream out;
  out.precision(6);
  out << "point " << i + 1 << " of " << scene.points.size() << " (d=" << p.d << " n=" << p.n << " nu=" << p.nu;
  if (p.dist == "lognormal") out << " lognormal sigma=" << p.sigma;
  else out << " alpha=" << p.alpha;
  out << " omega=" << p.omega << " " << to_string(p.boundary) << " " << to_string(p.placement)
      << (p.method != ExcludedMethod::automatic ? std::string(" method=") + to_string(p.method) : std::string())
      << (p.equilibrate ? " equilibrated" : "") << " seed=" << p.seed << ", " << to_string(scene.points[i].search)
      << ")";
  return out.str();
}

std::string scene_kind(const std::string& path) {
  const toml::table root = detail::read_scene_file(path).root;
  const std::string kind = root["kind"].value_or(std::string("contact"));
  if (kind != "contact" && kind != "dpm") throw InputError("kind", "must be 'contact' or 'dpm' (got '" + kind + "')");
  return kind;
}

Scene load_scene(const std::string& path, const std::string& scale) {
  return load_scene_text(detail::read_scene_file(path).text, scale, path);
}

Scene load_scene_text(const std::string& text, const std::string& scale, const std::string& name) {
  Scene s;
  detail::check_scale_name(scale);
  detail::SceneFile file = detail::parse_scene_text(text, name);
  const toml::table& root = file.root;
  s.source = std::move(file.text);
  s.scale = scale;
  check_keys(root, "", {"name", "description", "kind", "packings", "grid", "record", "scale"});
  if (root["kind"].value_or(std::string("contact")) != "contact")
    throw InputError("kind", "this scene is not a contact-search scene (kind = 'contact')");
  if (auto v = root["name"].value<std::string>(); v && !v->empty()) s.name = *v;
  else throw InputError("name", "is required (a non-empty string naming the scene and its result files)");
  for (char c : s.name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'))
      throw InputError("name", "may contain only letters, digits, '_' and '-'");
  if (auto v = root["description"].value<std::string>()) s.description = *v;

  const auto* packings = root["packings"].as_table();
  if (!packings) throw InputError("packings", "a [packings] table is required");
  PackingLists base;
  read_packings(*packings, base, "packings.", true);
  // [[packings.groups]]: parts of the scene that differ from [packings] in
  // some keys (e.g. a placement method per size ratio); their points follow
  // one another, group by group. A scale's override applies to every group.
  std::vector<PackingLists> groups;
  if (const auto* list = (*packings)["groups"].as_array()) {
    for (std::size_t i = 0; i < list->size(); ++i) {
      const std::string where = "packings.groups[" + std::to_string(i) + "].";
      const auto* t = list->get(i)->as_table();
      if (!t) throw InputError(where.substr(0, where.size() - 1), "must be a table of [packings] keys");
      PackingLists g = base;
      read_packings(*t, g, where);
      groups.push_back(std::move(g));
    }
    if (groups.empty()) throw InputError("packings.groups", "must hold at least one group");
  } else if ((*packings)["groups"]) {
    throw InputError("packings.groups", "must be an array of tables ([[packings.groups]])");
  } else {
    groups.push_back(base);
  }
  for (PackingLists& g : groups) {
    if (const auto* sp = detail::scale_section(root, scale, "packings", kSections))
      read_packings(*sp, g, "scale." + scale + ".packings.");
    check_lists(g);
  }
  if (const auto* g = root["grid"].as_table()) read_grid(*g, s.grid);
  if (const auto* r = root["record"].as_table()) read_record(*r, s.record);

  // Cartesian product, in a fixed order (the order of the result rows).
  for (const PackingLists& lists : groups)
  for (std::int64_t d : lists.d)
    for (const auto& dist : lists.dist)
      for (const auto& bnd : lists.boundary)
        for (const auto& plc : lists.placement)
          for (double alpha : lists.alpha)
            for (double omega : lists.omega)
              for (double sigma : lists.sigma)
                for (std::int64_t n : lists.n)
                  for (double nu : lists.nu)
                    for (std::int64_t seed : lists.seeds)
                      for (Search search : s.grid.searches) {
                        ScenePoint pt;
                        PackingSpec& p = pt.packing;
                        p.d = static_cast<int>(d);
                        p.n = static_cast<std::size_t>(n);
                        p.nu = nu;
                        p.dist = dist;
                        p.alpha = alpha;
                        p.omega = omega;
                        p.sigma = sigma;
                        p.boundary = parse_boundary(bnd);
                        p.placement = parse_placement(plc);
                        p.seed = static_cast<std::uint64_t>(seed);
                        if (p.placement == Placement::excluded) {  // random centres are neither grown nor equilibrated
                          p.method = lists.method;
                          p.equilibrate = lists.equilibrate;
                          p.sweeps = static_cast<int>(lists.sweeps);
                          p.stop = lists.stop;
                          p.moves = lists.moves;
                          p.stationary_tol = lists.stationary_tol;
                        }
                        pt.search = search;
                        s.points.push_back(pt);
                      }
  // Everything that would fail at generation fails here, before any work
  // (and before a journal is started), naming the scene key.
  std::map<std::string, bool> checked;
  for (const auto& pt : s.points) {
    if (!checked.emplace(packing_key(pt.packing), true).second) continue;
    try {
      check_packing_spec(pt.packing);
    } catch (const InputError& e) {
      const std::string what = e.what();
      throw InputError("packings." + e.field(), what.substr(std::min(what.size(), e.field().size() + 2)));
    }
  }
  return s;
}

}  // namespace hgrid
