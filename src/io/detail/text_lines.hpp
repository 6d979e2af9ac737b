// Line-by-line reading of text particle files, shared by the table, LAMMPS and
// MercuryDPM readers: line numbers, tokens, numbers, the snapshot asked for,
// and the messages that name the file, the line and the field.
#pragma once
#include <cstddef>
#include <optional>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace hgrid::detail {

/// Particles (rows) reserved up front at most: a file's declared count may lie.
inline constexpr std::size_t kReserveAtMost = std::size_t{1} << 20;

/// Lines of a text held in memory, numbered from 1; a UTF-8 byte-order mark
/// and the '\r' of CRLF line ends are dropped.
class Lines {
 public:
  Lines(std::string_view text, std::string name);
  /// The next line, false at the end.
  bool next(std::string_view& line);
  std::size_t number() const { return number_; }
  const std::string& name() const { return name_; }
  /// "name:line" of the current line.
  std::string where() const;

 private:
  std::string_view text_;
  std::size_t at_ = 0, number_ = 0;
  std::string name_;
};

/// Whitespace-separated tokens (space, tab, vertical tab, form feed).
std::vector<std::string_view> split_ws(std::string_view line);
/// The cells between `sep` characters, each with surrounding blanks trimmed.
std::vector<std::string_view> split_on(std::string_view line, char sep);
std::string_view trim(std::string_view s);
bool blank(std::string_view line);
std::string lower(std::string_view s);

/// The whole token as a number (strtod syntax, nothing left over); false
/// otherwise. Non-finite values are numbers here: callers check the range.
bool to_number(std::string_view token, double& v);

/// A token that must be a finite number: InputError(field, "'tok' is not a
/// finite number at <where>") otherwise.
double finite_number(std::string_view token, const std::string& field, const Lines& at);
/// Same, and > 0 (a radius, a diameter).
double positive_number(std::string_view token, const std::string& field, const Lines& at);
/// A count: a non-negative integer that fits, at most `max`.
std::size_t count_number(std::string_view token, const std::string& field, const Lines& at, std::size_t max);

/// The snapshot a reader takes from a file of `count`: `frame` from the
/// first (0-based) or from the end when negative, nothing: the last;
/// InputError("frame") naming the range and the file otherwise. Files of
/// one snapshot (tables, LAMMPS data, HDF5) take 0 or -1.
std::size_t resolve_frame(std::optional<std::int64_t> frame, std::size_t count, const std::string& name);

}  // namespace hgrid::detail
