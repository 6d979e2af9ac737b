// Strict key checking for scene files: an unknown key is an error naming it.
#pragma once
#include <set>
#include <string>
#include <toml++/toml.h>

#include "grid/error.hpp"

namespace hgrid::detail {

/// Throws InputError(where + key, ...) for any key of `t` not in `allowed`,
/// listing the allowed keys.
inline void check_keys(const toml::table& t, const std::string& where, const std::set<std::string>& allowed) {
  for (const auto& [k, v] : t) {
    const std::string key(k.str());
    if (!allowed.count(key)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw InputError(where + key, "unknown key (allowed: " + list + ")");
    }
  }
}

}  // namespace hgrid::detail
