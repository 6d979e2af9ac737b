// Input errors: every rejection names the offending field and the allowed range.
#pragma once
#include <cstdio>
#include <stdexcept>
#include <string>

namespace hgrid {

/// Thrown for bad user input (file contents, parameters). The command-line
/// tool turns it into a one-line message and exit status 2.
class InputError : public std::invalid_argument {
 public:
  InputError(const std::string& field, const std::string& problem)
      : std::invalid_argument(field + ": " + problem), field_(field) {}
  const std::string& field() const noexcept { return field_; }
  /// The message without its "field: " prefix.
  std::string problem() const { return std::string(what()).substr(field_.size() + 2); }

 private:
  std::string field_;
};

/// A number as messages print it: all 17 significant digits, so that the
/// value named is the value rejected.
inline std::string format_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace hgrid
