// printf-style formatting into a std::string (text reports built by the
// library for the tool to print).
#pragma once
#include <cstdio>
#include <string>

namespace hgrid {

/// std::snprintf(f, a...) as a std::string.
template <class... A>
std::string printf_string(const char* f, A... a) {
  const int n = std::snprintf(nullptr, 0, f, a...);
  std::string s(static_cast<std::size_t>(n > 0 ? n : 0) + 1, '\0');
  std::snprintf(s.data(), s.size(), f, a...);
  s.pop_back();
  return s;
}

}  // namespace hgrid
