#include "hgridlab/io/detail/table_reader.hpp"

#include <algorithm>
#include <optional>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/detail/text_lines.hpp"

namespace hgrid::detail {
namespace {

const char* const kAxisNames[3] = {"x", "y", "z"};

/// A header name without quotes, unit or '#', lower case.
std::string normalise(std::string_view name) {
  std::string s = lower(trim(name));
  s.erase(std::remove(s.begin(), s.end(), '"'), s.end());
  s.erase(std::remove(s.begin(), s.end(), '\''), s.end());
  const auto unit = s.find_first_of("[(");
  if (unit != std::string::npos && unit > 0) s.erase(unit);
  while (!s.empty() && s.front() == '#') s.erase(0, 1);
  return std::string(trim(s));
}

bool one_of(const std::string& s, std::initializer_list<const char*> names) {
  return std::any_of(names.begin(), names.end(), [&](const char* n) { return s == n; });
}

/// The axis (0, 1, 2) a name stands for, -1 for none; `scaled` is set for
/// LAMMPS's fractional coordinates.
int axis_of(const std::string& s, bool& scaled) {
  for (int a = 0; a < 3; ++a) {
    const std::string c(1, "xyz"[a]);
    if (s == c || s == c + "u" || s == "pos_" + c || s == "pos" + c || s == "position_" + c || s == "p" + c ||
        s == c + "_coord" || s == "coord_" + c || s == "pos." + c || s == "position." + c) {
      scaled = false;
      return a;
    }
    if (s == c + "s" || s == c + "su") {
      scaled = true;
      return a;
    }
  }
  return -1;
}

/// The columns of the plain layouts, by the number of values per line.
std::optional<Columns> plain_layout(std::size_t values) {
  Columns c;
  if (values == 1) c.size = 0;
  else if (values == 3) c.axis[0] = 0, c.axis[1] = 1, c.size = 2;
  else if (values == 4) c.axis[0] = 0, c.axis[1] = 1, c.axis[2] = 2, c.size = 3;
  else return std::nullopt;
  return c;
}

std::vector<std::string_view> cells_of(std::string_view line, char sep) {
  return sep ? split_on(line, sep) : split_ws(line);
}

/// "# format x_y_z_r" (Yade's export) or "# x y z r": the names, if the
/// comment reads as a header.
std::optional<std::vector<std::string>> commented_header(std::string_view rest) {
  auto toks = split_ws(rest);
  std::vector<std::string> names;
  if (toks.size() == 2 && lower(toks[0]) == "format") {
    for (auto part : split_on(toks[1], '_')) names.emplace_back(part);
  } else {
    const char sep = rest.find(',') != std::string_view::npos ? ',' : 0;
    for (auto t : cells_of(rest, sep)) names.emplace_back(t);
  }
  double v;
  for (const auto& n : names)
    if (n.empty() || to_number(n, v)) return std::nullopt;
  // A comment names the columns only if it names a size and x and y: "# d is
  // the diameter" above "x y r" lines is prose, not a header.
  const Columns c = map_columns(names);
  if (c.size < 0 || c.dims() < 2) return std::nullopt;
  return names;
}

void check_columns(const Columns& c, const std::string& header, const Lines& at) {
  if (c.size < 0)
    throw InputError("header", "no radius or diameter column in '" + header.substr(0, 80) + "' at " + at.where() +
                                   " (expected r|rad|radius or d|diam|diameter; files read: " + kParticleFormats + ")");
  if (c.dims() < 0)
    throw InputError("header", "columns x and y are both needed when either (or z) is given, at " + at.where());
}

}  // namespace

Columns map_columns(const std::vector<std::string>& names) {
  Columns c;
  int diameter = -1;
  for (int i = 0; i < static_cast<int>(names.size()); ++i) {
    const std::string s = normalise(names[i]);
    bool scaled = false;
    const int a = axis_of(s, scaled);
    if (a >= 0) {
      if (c.axis[a] < 0 || (c.scaled[a] && !scaled)) c.axis[a] = i, c.scaled[a] = scaled;  // real coordinates win
    } else if (c.size < 0 && one_of(s, {"r", "rad", "radius", "radii", "particle_radius"})) {
      c.size = i;
    } else if (diameter < 0 && one_of(s, {"d", "diam", "diameter", "dia", "particle_diameter"})) {
      diameter = i;
    }
  }
  if (c.size < 0 && diameter >= 0) c.size = diameter, c.diameter = true;
  return c;
}

ParticleSet parse_table(std::string_view text, const std::string& name) {
  Lines at(text, name);
  ParticleSet s;
  s.format = ParticleFormat::table;
  std::optional<Columns> cols;
  std::optional<std::vector<std::string>> comment_names;
  std::size_t ncells = 0;
  char sep = 0;
  int box_d = 0;
  std::string_view line;
  while (at.next(line)) {
    const std::string_view t = trim(line);
    if (t.empty()) continue;
    if (t.front() == '#') {
      const auto toks = split_ws(t.substr(1));
      const std::string key = toks.empty() ? "" : lower(toks[0]);
      if (key == "box") {
        if (toks.size() != 3 && toks.size() != 4)
          throw InputError("box", "'# box' needs 2 or 3 side lengths at " + at.where());
        std::array<double, 3> b{};
        for (std::size_t a = 1; a < toks.size(); ++a) b[a - 1] = positive_number(toks[a], "box", at);
        s.box = b;
        box_d = static_cast<int>(toks.size()) - 1;
      } else if (key == "boundary") {
        const std::string b = toks.size() > 1 ? lower(toks[1]) : "";
        if (b != "periodic" && b != "walls")
          throw InputError("boundary", "'# boundary' must be periodic or walls at " + at.where());
        s.boundary = b == "periodic" ? Boundary::periodic : Boundary::walls;
      } else if (!cols) {
        if (auto names = commented_header(t.substr(1))) comment_names = std::move(names);
      }
      continue;
    }
    if (!cols) {
      sep = t.find(',') != std::string_view::npos ? ',' : t.find(';') != std::string_view::npos ? ';' : 0;
      const auto cells = cells_of(t, sep);
      double v;
      const bool numeric = std::all_of(cells.begin(), cells.end(), [&](std::string_view c) { return to_number(c, v); });
      ncells = cells.size();
      if (!numeric) {
        cols = map_columns(std::vector<std::string>(cells.begin(), cells.end()));
        check_columns(*cols, std::string(t), at);
        if (cols->any_scaled()) throw InputError("header", "scaled coordinates (xs) need a LAMMPS dump's box, at " + at.where());
        continue;
      }
      if (comment_names && comment_names->size() == ncells) {
        cols = map_columns(*comment_names);
        check_columns(*cols, "", at);
      } else {
        cols = plain_layout(ncells);
        if (!cols)
          throw InputError("columns", std::to_string(ncells) + " numbers per line and no header at " + at.where() +
                                          ": expected 1 (r), 3 (x y r) or 4 (x y z r), or a header naming the columns");
      }
    }
    const auto cells = cells_of(t, sep);
    if (cells.size() != ncells)
      throw InputError("row", "expected " + std::to_string(ncells) + " values, got " + std::to_string(cells.size()) +
                                  " at " + at.where());
    const double size = positive_number(cells[cols->size], cols->diameter ? "diameter" : "radius", at);
    s.radii.push_back(cols->diameter ? size / 2 : size);
    for (int a = 0; a < cols->dims(); ++a) s.positions.push_back(finite_number(cells[cols->axis[a]], kAxisNames[a], at));
  }
  if (!cols) throw InputError("header", "no particles in " + name + " (expected " + kParticleFormats + ")");
  if (s.radii.empty()) throw InputError("particles", "no particle lines after the header in " + name);
  s.d = cols->dims() > 0 ? cols->dims() : box_d;
  if (s.box && box_d != s.d)
    throw InputError("box", "'# box' has " + std::to_string(box_d) + " sides but the columns are " +
                                std::to_string(s.d) + "D in " + name);
  return s;
}

}  // namespace hgrid::detail
