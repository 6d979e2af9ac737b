// Input errors: every rejection names the offending field and the allowed range.
#pragma once
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

 private:
  std::string field_;
};

}  // namespace hgrid
