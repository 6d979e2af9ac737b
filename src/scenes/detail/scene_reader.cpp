#include "hgridlab/scenes/detail/scene_reader.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "hgridlab/base/error.hpp"

namespace hgrid::detail {

SceneFile read_scene_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("scene", "cannot open '" + path + "'");
  std::stringstream buf;
  buf << in.rdbuf();
  return parse_scene_text(buf.str(), path);
}

SceneFile parse_scene_text(const std::string& text, const std::string& name) {
  try {
    return {text, toml::parse(text, name)};
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << e.description() << " at line " << e.source().begin.line;
    throw InputError("scene", msg.str() + " in " + name);
  }
}

void check_keys(const toml::table& t, const std::string& where, const std::set<std::string>& allowed) {
  for (const auto& [k, v] : t) {
    const std::string key(k.str());
    if (!allowed.count(key)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw InputError(where + key, "unknown key (allowed: " + list + ")");
    }
  }
}

void check_scale_name(const std::string& scale) {
  if (scale != "smoke" && scale != "default" && scale != "paper")
    throw InputError("scale", "must be smoke, default or paper (got '" + scale + "')");
}

const toml::table* scale_section(const toml::table& root, const std::string& scale, const std::string& section,
                                 const SceneSections& sections) {
  const auto* scales = root["scale"].as_table();
  if (!scales) {
    if (root.contains("scale")) throw InputError("scale", "must be a table of [scale.<name>.<section>] tables");
    return nullptr;
  }
  check_keys(*scales, "scale.", {"smoke", "default", "paper"});
  std::set<std::string> names;
  for (const auto& [name, keys] : sections) names.insert(name);
  for (const auto& [sk, sv] : *scales) {
    const std::string where = "scale." + std::string(sk.str());
    const auto* st = sv.as_table();
    if (!st) throw InputError(where, "must be a table");
    check_keys(*st, where + ".", names);
    for (const auto& [name, sub] : *st) {
      const std::string w = where + "." + std::string(name.str());
      const auto* subt = sub.as_table();
      if (!subt) throw InputError(w, "must be a table");
      check_keys(*subt, w + ".", sections.at(std::string(name.str())));
    }
  }
  const auto* st = (*scales)[scale].as_table();
  return st ? (*st)[section].as_table() : nullptr;
}

const toml::table& section(const toml::table& root, const std::string& name) {
  static const toml::table empty;
  const auto* t = root[name].as_table();
  if (root.contains(name) && !t) throw InputError(name, "must be a table");
  return t ? *t : empty;
}

namespace {
std::string key_name(const std::string& sec, const std::string& key) { return sec.empty() ? key : sec + "." + key; }
}  // namespace

double number(const toml::table& t, const std::string& sec, const std::string& key, double def) {
  const auto* n = t.get(key);
  if (!n) return def;
  if (auto v = n->value<double>(); v && std::isfinite(*v)) return *v;
  throw InputError(key_name(sec, key), "must be a finite number");
}

std::uint64_t count(const toml::table& t, const std::string& sec, const std::string& key, std::uint64_t def) {
  const auto* n = t.get(key);
  if (!n) return def;
  auto v = n->value<std::int64_t>();
  if (!v || *v < 0) throw InputError(key_name(sec, key), "must be an integer >= 0");
  return static_cast<std::uint64_t>(*v);
}

std::string text(const toml::table& t, const std::string& sec, const std::string& key, const std::string& def) {
  const auto* n = t.get(key);
  if (!n) return def;
  if (auto v = n->value<std::string>()) return *v;
  throw InputError(key_name(sec, key), "must be a string");
}

bool flag(const toml::table& t, const std::string& sec, const std::string& key, bool def) {
  const auto* n = t.get(key);
  if (!n) return def;
  if (auto v = n->value<bool>()) return *v;
  throw InputError(key_name(sec, key), "must be true or false");
}

namespace {
/// One value or a non-empty array of them, each read by `one`.
template <class One>
auto list_of(const toml::node& n, const std::string& key, One one) {
  std::vector<decltype(one(n))> out;
  if (const auto* a = n.as_array()) {
    for (const auto& e : *a) out.push_back(one(e));
  } else {
    out.push_back(one(n));
  }
  if (out.empty()) throw InputError(key, "must not be empty");
  return out;
}
}  // namespace

std::vector<double> numbers(const toml::node& n, const std::string& key) {
  return list_of(n, key, [&](const toml::node& e) {
    const auto v = e.value<double>();
    if (!v) throw InputError(key, "must be a number");
    if (!std::isfinite(*v)) throw InputError(key, "must be finite");
    return *v;
  });
}

std::vector<std::int64_t> whole_numbers(const toml::node& n, const std::string& key, std::int64_t lo, std::int64_t hi) {
  std::string range = "[";  // appended piece by piece: GCC 12 warns (-Wrestrict) on "[" + string
  range += std::to_string(lo);
  range += ", ";
  range += std::to_string(hi);
  range += ']';
  return list_of(n, key, [&](const toml::node& e) {
    if (!e.is_integer()) throw InputError(key, "must be whole numbers in " + range + ", written as integers (100000, not 1e5)");
    const std::int64_t v = e.value<std::int64_t>().value_or(lo - 1);
    if (v < lo || v > hi) throw InputError(key, "must be whole numbers in " + range + " (got " + std::to_string(v) + ")");
    return v;
  });
}

std::vector<std::string> strings(const toml::node& n, const std::string& key) {
  return list_of(n, key, [&](const toml::node& e) {
    auto s = e.value<std::string>();
    if (!s) throw InputError(key, "must be a string or a list of strings");
    return *s;
  });
}

double one_number(const toml::node& n, const std::string& key) {
  if (n.is_array()) throw InputError(key, "takes one number, not a list");
  return numbers(n, key).front();
}

std::string one_string(const toml::node& n, const std::string& key) {
  if (n.is_array()) throw InputError(key, "takes one string, not a list");
  return strings(n, key).front();
}

}  // namespace hgrid::detail
