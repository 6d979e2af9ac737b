// The one reader of scene files (TOML), for both kinds (contact and DPM):
// the file parse, strict keys, the [scale.<name>] overrides and typed getters.
// Every error is an InputError naming the key.
#pragma once
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <toml++/toml.h>
#include <vector>

namespace hgrid::detail {

/// The allowed keys of each section of a scene kind.
using SceneSections = std::map<std::string, std::set<std::string>>;

struct SceneFile {
  std::string text;  // stored with the results
  toml::table root;
};

/// Reads and parses a scene file; InputError("scene", ...) if unreadable.
SceneFile read_scene_file(const std::string& path);
/// Parses a scene's text; `name` names it in messages.
SceneFile parse_scene_text(const std::string& text, const std::string& name);

/// Throws InputError(where + key, ...) for any key of `t` not in `allowed`,
/// listing the allowed keys.
void check_keys(const toml::table& t, const std::string& where, const std::set<std::string>& allowed);

/// "smoke", "default" or "paper"; anything else throws InputError("scale").
void check_scale_name(const std::string& scale);

/// Checks the [scale] table (its scales, their sections and keys) and returns
/// the table [scale.<scale>.<section>] (nullptr when absent).
const toml::table* scale_section(const toml::table& root, const std::string& scale, const std::string& section,
                                 const SceneSections& sections);

/// The section `name` of root (an empty table when absent; InputError when
/// it is not a table).
const toml::table& section(const toml::table& root, const std::string& name);

// Typed getters: the value of key in table t (named sec.key in messages), or
// def when absent. A value of another type, or a non-finite number, throws.
double number(const toml::table& t, const std::string& sec, const std::string& key, double def);
std::uint64_t count(const toml::table& t, const std::string& sec, const std::string& key, std::uint64_t def);
std::string text(const toml::table& t, const std::string& sec, const std::string& key, const std::string& def);
bool flag(const toml::table& t, const std::string& sec, const std::string& key, bool def);

/// A number or a non-empty array of finite numbers, as a list (`key` names it).
std::vector<double> numbers(const toml::node& n, const std::string& key);
/// A whole number or a non-empty array of them, each in [lo, hi]: TOML
/// integers only (1e5 is a float in TOML, refused with the form to write).
std::vector<std::int64_t> whole_numbers(const toml::node& n, const std::string& key, std::int64_t lo, std::int64_t hi);
/// One number (an array, even of one, is refused: the key takes one value).
double one_number(const toml::node& n, const std::string& key);
/// One string (likewise).
std::string one_string(const toml::node& n, const std::string& key);

/// A string or a non-empty array of strings, as a list.
std::vector<std::string> strings(const toml::node& n, const std::string& key);

}  // namespace hgrid::detail
