#include "hgridlab/io/detail/lammps_reader.hpp"

#include <algorithm>
#include <optional>

#include "hgridlab/base/error.hpp"
#include "hgridlab/grid/tilted_box.hpp"
#include "hgridlab/io/detail/table_reader.hpp"
#include "hgridlab/io/detail/text_lines.hpp"

namespace hgrid::detail {
namespace {

/// Lines read before the first "N atoms" line of a data file's header is
/// given up on.
constexpr int kDataHeaderLines = 60;

std::string_view before_comment(std::string_view line) { return trim(line.substr(0, line.find('#'))); }

bool is_section(std::string_view body) {
  double v;
  return !body.empty() && !to_number(split_ws(body)[0], v);
}

/// A 2D dump's boundary from x and y alone (LAMMPS writes z's flag, `p`, too).
void planar_boundary(ParticleSet& s) {
  if (s.d != 2 || !s.mixed_boundary) return;
  const int periodic = s.periodic_axes[0] + s.periodic_axes[1];
  if (periodic == 1) return;
  s.mixed_boundary = false;
  s.boundary = periodic == 2 ? Boundary::periodic : Boundary::walls;
}

/// Box sides from lo/hi pairs, positions moved to the lower corner, and a 2D
/// system (LAMMPS keeps z: every z = 0 in a box straddling it) made 2D.
void finish(ParticleSet& s, const std::array<double, 3>& lo, const std::array<double, 3>& hi, const std::string& name) {
  std::array<double, 3> side{};
  for (int a = 0; a < 3; ++a) {
    side[a] = hi[a] - lo[a];
    if (!(side[a] > 0) || !std::isfinite(side[a]))
      throw InputError("box", "the box bounds of axis " + std::string(1, "xyz"[a]) + " must have lo < hi in " + name);
  }
  s.box = side;
  if (!s.has_positions()) return;
  const std::size_t n = s.size();
  // LAMMPS keeps z in 2D (every z the same, usually 0, in any zlo zhi: a
  // 2D run's write_data gives -0.5 0.5 or 0 1): a file whose z are all
  // equal is 2D (two particles at least: one says nothing).
  bool flat = n > 1;
  for (std::size_t i = 1; flat && i < n; ++i) flat = s.positions[3 * i + 2] == s.positions[2];
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) s.positions[3 * i + a] -= lo[a];
  if (!flat) return;
  if (s.tilt[1] != 0 || s.tilt[2] != 0)
    throw InputError("box", name + " is 2D (every z equal) but its box tilts z (xz, yz not 0)");
  std::vector<double> xy;
  xy.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i) xy.push_back(s.positions[3 * i]), xy.push_back(s.positions[3 * i + 1]);
  s.positions = std::move(xy);
  s.d = 2;
}

/// A tilt beyond LAMMPS's limit (grid/tilted_box.hpp) is refused at `where`.
void check_tilt_limit(const std::array<double, 3>& tilt, const std::array<double, 3>& lo,
                      const std::array<double, 3>& hi, const std::string& field, const std::string& where) {
  const TiltedBox<3> box{{hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}, tilt};
  if (const std::string e = box.beyond_limit(); !e.empty()) throw InputError(field, e + " at " + where);
}

/// The next non-blank line, or InputError(field) at the end of the text.
std::string_view next_content(Lines& at, const std::string& field, const std::string& what) {
  std::string_view line;
  while (at.next(line))
    if (!blank(line)) return line;
  throw InputError(field, at.name() + " ends before " + what);
}

/// A 3D set of `f` (a LAMMPS file keeps z even in 2D).
ParticleSet empty_set(ParticleFormat f) {
  ParticleSet s;
  s.format = f;
  s.d = 3;
  return s;
}

void reserve(ParticleSet& s, std::size_t n, int coords) {
  const std::size_t r = std::min(n, kReserveAtMost);
  s.radii.reserve(r);
  s.positions.reserve(r * coords);
}

}  // namespace

bool looks_like_lammps_data(std::string_view text) {
  Lines at(text, "");
  std::string_view line;
  if (!at.next(line)) return false;  // the title
  for (int i = 0; i < kDataHeaderLines && at.next(line); ++i) {
    const std::string_view body = before_comment(line);
    if (body.empty()) continue;
    const auto toks = split_ws(body);
    double v;
    if (toks.size() == 2 && toks[1] == "atoms" && to_number(toks[0], v)) return true;
    if (is_section(body)) return false;
  }
  return false;
}

ParticleSet parse_lammps_data(std::string_view text, const std::string& name) {
  Lines at(text, name);
  ParticleSet s = empty_set(ParticleFormat::lammps_data);
  std::optional<std::size_t> n;
  std::array<double, 3> lo{-0.5, -0.5, -0.5}, hi{0.5, 0.5, 0.5};  // LAMMPS's defaults
  std::string tilt_at;  // file:line of the tilts
  std::string_view line;
  at.next(line);  // the title
  bool header = true;
  while (at.next(line)) {
    const std::string_view body = before_comment(line);
    if (body.empty()) continue;
    const auto toks = split_ws(body);
    if (is_section(body)) {
      header = false;
      if (body != "Atoms") continue;
      const auto hash = line.find('#');
      const std::string style = hash == std::string_view::npos ? "" : lower(trim(line.substr(hash + 1)));
      if (!style.empty() && style != "sphere")
        throw InputError("atom_style", "the Atoms section is '" + style + "' at " + at.where() +
                                           "; hgridlab reads atom_style sphere (id type diameter density x y z)");
      if (!n) throw InputError("atoms", "no 'N atoms' line before the Atoms section in " + name);
      check_tilt_limit(s.tilt, lo, hi, "box", tilt_at);
      reserve(s, *n, 3);
      for (std::size_t i = 0; i < *n; ++i) {
        const auto row = split_ws(before_comment(
            next_content(at, "Atoms", std::to_string(*n) + " atoms are read (" + std::to_string(i) + " found)")));
        if (row.size() != 7 && row.size() != 10)
          throw InputError("Atoms", "expected 7 values (id type diameter density x y z) or 10 (and image flags), got " +
                                        std::to_string(row.size()) + " at " + at.where() +
                                        "; hgridlab reads atom_style sphere");
        s.radii.push_back(positive_number(row[2], "diameter", at) / 2);
        for (int a = 0; a < 3; ++a) s.positions.push_back(finite_number(row[4 + a], std::string(1, "xyz"[a]), at));
      }
      finish(s, lo, hi, name);
      return s;
    }
    if (!header) continue;  // the body of another section
    if (toks.size() == 2 && toks[1] == "atoms") {
      n = count_number(toks[0], "atoms", at, kMaxParticles);
      if (*n == 0) throw InputError("atoms", "the file declares 0 atoms at " + at.where());
      check_memory("atoms", *n, kReadBytesPerParticle, "reading a LAMMPS data file");
    } else if (toks.size() == 4 && toks[2].size() == 3 && toks[2].substr(1) == "lo" &&
               toks[3].size() == 3 && toks[3].substr(1) == "hi" && toks[2][0] == toks[3][0] &&
               (toks[2][0] == 'x' || toks[2][0] == 'y' || toks[2][0] == 'z')) {
      const int a = toks[2][0] - 'x';
      lo[a] = finite_number(toks[0], "box", at);
      hi[a] = finite_number(toks[1], "box", at);
    } else if (toks.size() == 6 && toks[3] == "xy" && toks[4] == "xz" && toks[5] == "yz") {
      // LAMMPS writes the tilts of any triclinic box, zero ones too (a shear
      // run starts from one): a box without tilt is orthogonal.
      for (int k = 0; k < 3; ++k) s.tilt[k] = finite_number(toks[k], "box", at);
      tilt_at = at.where();
    }
  }
  throw InputError("Atoms", "no 'Atoms' section in " + name);
}

ParticleSet parse_lammps_dump(std::string_view text, const std::string& name, std::optional<std::int64_t> frame) {
  // The snapshots: one ATOMS item each.
  std::size_t snapshots = 0;
  {
    Lines count(text, name);
    std::string_view l;
    while (count.next(l))
      if (trim(l).substr(0, 5) == "ITEM:" && trim(trim(l).substr(5)).substr(0, 5) == "ATOMS") ++snapshots;
  }
  // (none: the items below say what is missing)
  const std::size_t target = snapshots > 0 ? resolve_frame(frame, snapshots, name) : 0;
  std::size_t index = 0;  // of the next ATOMS item
  Lines at(text, name);
  ParticleSet s = empty_set(ParticleFormat::lammps_dump);
  std::optional<std::size_t> n;
  std::optional<std::array<double, 3>> lo, hi;
  std::array<std::array<bool, 2>, 3> shrink{};  // per axis, lo and hi: LAMMPS's s or m (bounds follow the atoms)
  std::string_view line;
  bool skipping = false;  // inside an ITEM this reader does not use
  while (at.next(line)) {
    const std::string_view t = trim(line);
    if (t.empty()) continue;
    if (t.substr(0, 5) != "ITEM:") {
      if (skipping) continue;
      throw InputError("ITEM", "expected an 'ITEM:' line at " + at.where());
    }
    skipping = false;
    const std::string_view item = trim(t.substr(5));
    if (item == "NUMBER OF ATOMS") {
      n = count_number(trim(next_content(at, "NUMBER OF ATOMS", "the number of atoms")), "NUMBER OF ATOMS", at,
                       kMaxParticles);
      check_memory("NUMBER OF ATOMS", *n, kReadBytesPerParticle, "reading a LAMMPS dump");
    } else if (item.substr(0, 10) == "BOX BOUNDS") {
      auto flags = split_ws(item.substr(10));
      // A triclinic dump: "xy xz yz" before the flags, and a tilt after each
      // pair of bounds; with every tilt 0 the bounds are the box's.
      const bool tilted = flags.size() == 6 && flags[0] == "xy" && flags[1] == "xz" && flags[2] == "yz";
      if (tilted) flags.erase(flags.begin(), flags.begin() + 3);
      else if (std::find(flags.begin(), flags.end(), "xy") != flags.end())
        throw InputError("BOX BOUNDS", "expected 'xy xz yz' and three boundary flags at " + at.where());
      if (flags.size() != 3)
        throw InputError("BOX BOUNDS", "expected three boundary flags (pp pp pp, ff ff ff, ...) at " + at.where());
      int periodic = 0;
      s.mixed_boundary = false;
      for (int a = 0; a < 3; ++a) {
        periodic += s.periodic_axes[a] = flags[a] == "pp";
        for (int side = 0; side < 2; ++side)
          shrink[a][side] = flags[a].size() == 2 && (flags[a][side] == 's' || flags[a][side] == 'm');
      }
      if (periodic == 3) s.boundary = Boundary::periodic;
      else if (periodic == 0) s.boundary = Boundary::walls;
      else s.mixed_boundary = true;
      lo.emplace(), hi.emplace();
      for (int a = 0; a < 3; ++a) {
        const auto b = split_ws(next_content(at, "BOX BOUNDS", "the box bounds"));
        if (b.size() != (tilted ? 3u : 2u))
          throw InputError("BOX BOUNDS", std::string("expected '") + (tilted ? "lo hi tilt" : "lo hi") + "' at " + at.where());
        (*lo)[a] = finite_number(b[0], "BOX BOUNDS", at);
        (*hi)[a] = finite_number(b[1], "BOX BOUNDS", at);
        s.tilt[a] = tilted ? finite_number(b[2], "BOX BOUNDS", at) : 0.0;  // xy, xz, yz in this order
      }
      if (tilted) {
        // A triclinic dump's bounds enclose the tilted box (LAMMPS's dump
        // documentation): xlo_bound = xlo + min(0, xy, xz, xy + xz),
        // xhi_bound = xhi + max(0, xy, xz, xy + xz), ylo_bound = ylo + min(0, yz),
        // yhi_bound = yhi + max(0, yz).
        const double xy = s.tilt[0], xz = s.tilt[1], yz = s.tilt[2];
        (*lo)[0] -= std::min({0.0, xy, xz, xy + xz});
        (*hi)[0] -= std::max({0.0, xy, xz, xy + xz});
        (*lo)[1] -= std::min(0.0, yz);
        (*hi)[1] -= std::max(0.0, yz);
        check_tilt_limit(s.tilt, *lo, *hi, "BOX BOUNDS", at.where());
      }
    } else if (item.substr(0, 5) == "ATOMS") {
      if (!n || !lo) throw InputError("ATOMS", "'ITEM: NUMBER OF ATOMS' and 'ITEM: BOX BOUNDS' must come first, at " + at.where());
      if (index++ != target) {  // another snapshot: its rows are passed over
        for (std::size_t i = 0; i < *n; ++i)
          next_content(at, "ATOMS", std::to_string(*n) + " atoms are read (" + std::to_string(i) + " found)");
        continue;
      }
      s.frame = target;
      s.frames = snapshots;
      const auto names_sv = split_ws(item.substr(5));
      const std::vector<std::string> names(names_sv.begin(), names_sv.end());
      const Columns c = map_columns(names);
      if (c.size < 0)
        throw InputError("ATOMS", "no radius or diameter column at " + at.where() + " (dump ... radius or diameter)");
      const int dims = c.dims();
      if (dims < 0) throw InputError("ATOMS", "coordinates need x and y (and z in 3D) at " + at.where());
      if (s.tilted() && c.any_scaled() && !(c.scaled[0] && c.scaled[1] && (dims == 2 || c.scaled[2])))
        throw InputError("ATOMS", "a tilted box's dump with scaled and unscaled coordinates mixed at " + at.where() +
                                      " (dump xs ys zs, or x y z)");
      reserve(s, *n, dims);
      for (std::size_t i = 0; i < *n; ++i) {
        const auto row = split_ws(next_content(at, "ATOMS", std::to_string(*n) + " atoms are read (" + std::to_string(i) + " found)"));
        if (row.size() != names.size())
          throw InputError("ATOMS", "expected " + std::to_string(names.size()) + " values, got " +
                                        std::to_string(row.size()) + " at " + at.where());
        const double size = positive_number(row[c.size], c.diameter ? "diameter" : "radius", at);
        s.radii.push_back(c.diameter ? size / 2 : size);
        std::array<double, 3> v{};
        for (int a = 0; a < dims; ++a) v[a] = finite_number(row[c.axis[a]], std::string(1, "xyz"[a]), at);
        // Scaled coordinates are fractional: x = lo + H s in a tilted box.
        const double tx = c.scaled[1] ? s.tilt[0] * v[1] : 0.0, tz = dims == 3 && c.scaled[2] ? v[2] : 0.0;
        for (int a = 0; a < dims; ++a) {
          if (!c.scaled[a]) {
            s.positions.push_back(v[a]);
            continue;
          }
          double x = (*lo)[a] + v[a] * ((*hi)[a] - (*lo)[a]);
          if (a == 0) x += tx + s.tilt[1] * tz;
          if (a == 1) x += s.tilt[2] * tz;
          s.positions.push_back(x);
        }
      }
      if (s.radii.empty())
        throw InputError("ATOMS", "snapshot " + std::to_string(target) + " of " + name +
                                      " has no atoms; choose another with --frame");
      // Shrink-wrapped bounds (s, m) follow the atoms only when LAMMPS
      // reneighbours, so a dump between may hold centres just beyond them:
      // the bounds move out to those centres, as LAMMPS's next would.
      for (int a = 0; a < dims && !s.tilted(); ++a)
        for (std::size_t i = 0; i < s.size(); ++i) {
          const double x = s.positions[std::size_t(dims) * i + a];
          if (shrink[a][0] && x < (*lo)[a]) (*lo)[a] = x;
          if (shrink[a][1] && x > (*hi)[a]) (*hi)[a] = x;
        }
      if (dims == 2) {  // a 2D dump: x and y only
        if (s.tilt[1] != 0 || s.tilt[2] != 0)
          throw InputError("BOX BOUNDS", name + " is 2D (x and y only) but its box tilts z (xz, yz not 0)");
        s.d = 2;
        for (std::size_t i = 0; i < s.size(); ++i)
          for (int a = 0; a < 2; ++a) s.positions[2 * i + a] -= (*lo)[a];
        s.box = std::array<double, 3>{(*hi)[0] - (*lo)[0], (*hi)[1] - (*lo)[1], 0};
        if (!((*s.box)[0] > 0 && (*s.box)[1] > 0)) throw InputError("BOX BOUNDS", "lo must be < hi in " + name);
        planar_boundary(s);
        return s;
      }
      finish(s, *lo, *hi, name);
      planar_boundary(s);
      return s;  // the chosen snapshot only
    } else {
      skipping = true;  // TIMESTEP, UNITS, TIME, ...: their values are not needed
    }
  }
  throw InputError("ATOMS", "no 'ITEM: ATOMS' section in " + name);
}

}  // namespace hgrid::detail
