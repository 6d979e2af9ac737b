// MercuryDPM's .restart file (docs/record/MERCURYDPM_FILES.md section 3, read from
// its writers: DPMBase::write, Kernel/DPMBase.cc; ParticleHandler::write and
// BaseParticle::write; BaseWall::write and InfiniteWall; PeriodicBoundary::write,
// LeesEdwardsBoundary::write and ShearBoxBoundary::write in Kernel/Boundaries).
// Objects are "Type key value... key value..." lines: a keyword is a token
// that starts with a letter (not nan or inf), its values the numbers up to
// the next keyword, so no field's offset is assumed.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/detail/mercury_reader.hpp"
#include "hgridlab/io/detail/text_lines.hpp"

namespace hgrid::detail {
namespace {

/// One object line: its type and its keys' values (numbers only).
struct Object {
  std::string type;
  std::map<std::string, std::vector<double>, std::less<>> values;
  /// The k numbers after `key`, or InputError(field) at `at`.
  std::vector<double> get(const std::string& key, std::size_t k, const std::string& field, const Lines& at) const {
    const auto it = values.find(key);
    if (it == values.end() || it->second.size() < k)
      throw InputError(field, type + " line without " + std::to_string(k) + " value" + (k > 1 ? "s" : "") + " after '" +
                                  key + "' at " + at.where());
    return it->second;
  }
};

bool keyword(std::string_view t) {
  if (t.empty() || !std::isalpha(static_cast<unsigned char>(t[0]))) return false;
  const std::string l = lower(t);
  return l != "nan" && l != "inf" && l != "infinity" && l != "-nan";
}

Object parse_object(std::string_view line, const std::string& field, const Lines& at) {
  const auto toks = split_ws(line);
  Object o;
  if (toks.empty()) throw InputError(field, "an empty line at " + at.where());
  o.type = std::string(toks[0]);
  std::vector<double>* current = nullptr;
  for (std::size_t i = 1; i < toks.size(); ++i) {
    if (keyword(toks[i])) {
      current = &o.values[std::string(toks[i])];
      continue;
    }
    double v;
    if (current && to_number(toks[i], v)) current->push_back(v);  // other tokens (NO_FILE, names) are passed over
  }
  return o;
}

/// "Section N" (Walls 4, Boundaries 1, Particles 60): N, else nothing.
std::optional<std::size_t> section(std::string_view line, std::string_view name, const Lines& at) {
  const auto toks = split_ws(line);
  if (toks.size() != 2 || toks[0] != name) return std::nullopt;
  return count_number(toks[1], std::string(name), at, kMaxParticles);
}

/// The periodicity along one axis: the range [lo, hi] and the lattice vector
/// of the images across it.
struct Period {
  double lo = 0, hi = 0;
  std::array<double, 3> vec{};
};

}  // namespace

bool looks_like_mercury_restart(std::string_view text) {
  Lines at(text, "");
  std::string_view line;
  while (at.next(line) && blank(line)) {
  }
  const auto toks = split_ws(line);
  return toks.size() >= 2 && (toks[0] == "MercuryDPM" || toks[0] == "restart_version");
}

ParticleSet parse_mercury_restart(std::string_view text, const std::string& name) {
  Lines at(text, name);
  std::string_view line;
  while (at.next(line) && blank(line)) {
  }
  const auto head = split_ws(line);
  if (head.size() < 2 || (head[1] != "1.0" && head[1] != "0.14"))
    throw InputError("restart_version", std::string("MercuryDPM restart version '") +
                                            std::string(head.size() > 1 ? head[1] : "") + "' at " + at.where() +
                                            ": hgridlab reads the layout of versions 1.0 and 0.14 (MercuryDPM since 2018)");
  ParticleSet s;
  s.format = ParticleFormat::mercury_restart;
  std::array<double, 3> dmin{}, dmax{};
  bool domain = false;
  int d = 0;
  bool particles = false;  // the Particles section was read
  std::array<std::optional<Period>, 3> period;
  std::array<std::array<std::optional<double>, 2>, 3> wall;  // InfiniteWall planes: [axis][-e, +e]
  const auto periodic = [&](int a, double lo, double hi, std::array<double, 3> vec, const std::string& what) {
    if (period[a]) throw InputError("Boundaries", "two periodic boundaries across axis " + std::string(1, "xyz"[a]) +
                                                      " (" + what + ") at " + at.where());
    if (!(hi > lo)) throw InputError("Boundaries", what + " with an empty range at " + at.where());
    period[a] = Period{lo, hi, vec};
  };
  while (at.next(line)) {
    if (blank(line)) continue;
    const auto toks = split_ws(line);
    if (toks[0] == "xMin") {
      const Object o = parse_object("domain " + std::string(line), "domain", at);
      for (int a = 0; a < 3; ++a) {
        const std::string ax(1, "xyz"[a]);
        dmin[a] = o.get(ax + "Min", 1, "domain", at)[0];
        dmax[a] = o.get(ax + "Max", 1, "domain", at)[0];
      }
      domain = true;
    } else if (toks[0] == "systemDimensions") {
      const Object o = parse_object("system " + std::string(line), "systemDimensions", at);
      const double v = o.get("systemDimensions", 1, "systemDimensions", at)[0];
      if (v != 2 && v != 3) throw InputError("systemDimensions", "must be 2 or 3 at " + at.where());
      d = static_cast<int>(v);
      if (o.values.count("numberOfProcessors") && o.get("numberOfProcessors", 1, "numberOfProcessors", at)[0] > 1)
        throw InputError("numberOfProcessors", "an MPI run's restart file holds one rank's particles (at " +
                                                   at.where() + "); hgridlab reads a serial run's");
    } else if (const auto w = section(line, "Walls", at)) {
      for (std::size_t k = 0; k < *w; ++k) {
        if (!at.next(line)) throw InputError("Walls", name + " ends inside its Walls section");
        const Object o = parse_object(line, "Walls", at);
        if (o.type != "InfiniteWall") continue;  // other shapes: not a box face
        const auto p = o.get("position", 3, "Walls", at);
        std::array<double, 3> n{};
        if (o.values.count("normal")) {
          const auto v = o.get("normal", 3, "Walls", at);
          n = {v[0], v[1], v[2]};
        } else {  // the image of (1, 0, 0) under the orientation quaternion (Quaternion::getAxis)
          const auto q = o.get("orientation", 4, "Walls", at);
          n = {q[0] * q[0] + q[1] * q[1] - q[2] * q[2] - q[3] * q[3], 2 * (q[1] * q[2] + q[0] * q[3]),
               2 * (q[1] * q[3] - q[0] * q[2])};
        }
        for (int a = 0; a < 3; ++a)
          if (std::abs(std::abs(n[a]) - 1) < 1e-9) wall[a][n[a] > 0] = p[a];  // n points out of the domain
      }
    } else if (const auto b = section(line, "Boundaries", at)) {
      for (std::size_t k = 0; k < *b; ++k) {
        if (!at.next(line)) throw InputError("Boundaries", name + " ends inside its Boundaries section");
        const Object o = parse_object(line, "Boundaries", at);
        if (o.type == "PeriodicBoundary" || o.type == "TimeDependentPeriodicBoundary") {
          const auto n = o.get("normal", 3, "Boundaries", at);
          const double left = o.get("distanceLeft", 1, "Boundaries", at)[0];
          const double right = o.get("distanceRight", 1, "Boundaries", at)[0];
          int a = -1;
          for (int c = 0; c < 3; ++c)
            if (std::abs(std::abs(n[c]) - 1) < 1e-9) a = c;
          if (a < 0)
            throw InputError("Boundaries", o.type + " with a normal along no axis at " + at.where() +
                                               "; hgridlab's boxes are periodic along the axes");
          const double sign = n[a] > 0 ? 1 : -1;
          std::array<double, 3> vec{};
          if (o.values.count("shift")) {  // n (b - a) plus a shift within the plane
            const auto v = o.get("shift", 3, "Boundaries", at);
            vec = {sign * v[0], sign * v[1], sign * v[2]};
          } else {
            vec[a] = right - left;
          }
          periodic(a, sign > 0 ? left : -right, sign > 0 ? right : -left, vec, o.type);
        } else if (o.type == "LeesEdwardsBoundary" || o.type == "ShearBoxBoundary") {
          // x periodic on [left, right]; y on [down, up], crossing it moves x
          // by the shift (LeesEdwardsBoundary::shiftVerticalPosition).
          const double left = o.get("left", 1, "Boundaries", at)[0], right = o.get("right", 1, "Boundaries", at)[0];
          const double down = o.get("down", 1, "Boundaries", at)[0], up = o.get("up", 1, "Boundaries", at)[0];
          const double shift = o.values.count("shift") ? o.get("shift", 1, "Boundaries", at)[0] : 0.0;
          periodic(0, left, right, {right - left, 0, 0}, o.type);
          periodic(1, down, up, {shift, up - down, 0}, o.type);
        } else if (o.type.find("PeriodicBoundary") != std::string::npos) {
          throw InputError("Boundaries", o.type + " at " + at.where() + " is no box of axis-aligned faces");
        }  // insertion, deletion and other boundaries do not shape the box
      }
    } else if (const auto p = section(line, "Particles", at)) {
      check_memory("Particles", *p, kReadBytesPerParticle, "reading a MercuryDPM restart file");
      if (d == 0) throw InputError("systemDimensions", "no 'systemDimensions' line before the Particles in " + name);
      if (!domain) throw InputError("domain", "no 'xMin ... zMax' line before the Particles in " + name);
      s.radii.reserve(std::min<std::size_t>(*p, kReserveAtMost));
      s.positions.reserve(std::min<std::size_t>(*p, kReserveAtMost) * d);
      for (std::size_t k = 0; k < *p; ++k) {
        if (!at.next(line) || split_ws(line).size() < 4)  // the end, or the next section's "Name N"
          throw InputError("Particles", "the section declares " + std::to_string(*p) + " particles, " + name +
                                            " has " + std::to_string(k) + " (at " + at.where() + ")");
        const Object o = parse_object(line, "Particles", at);
        const auto x = o.get("position", 3, "Particles", at);
        const double r = o.get("radius", 1, "Particles", at)[0];
        if (!(std::isfinite(r) && r > 0)) throw InputError("radius", "must be finite and > 0 at " + at.where());
        for (int a = 0; a < d; ++a) {
          if (!std::isfinite(x[a])) throw InputError("position", "not finite at " + at.where());
          s.positions.push_back(x[a]);
        }
        s.radii.push_back(r);
      }
      particles = true;
      break;  // interactions and the grid's line follow: not needed
    }
  }
  if (!particles) throw InputError("Particles", "no 'Particles' section in " + name);
  s.d = d;
  // The box: periodic where a boundary says, else between the walls, else the domain.
  int n_periodic = 0;
  std::array<double, 3> lo{}, hi{};
  for (int a = 0; a < d; ++a) {
    if (period[a]) {
      ++n_periodic;
      s.periodic_axes[a] = true;
      lo[a] = period[a]->lo, hi[a] = period[a]->hi;
    } else if (wall[a][0] && wall[a][1]) {
      lo[a] = *wall[a][0], hi[a] = *wall[a][1];
    } else {
      lo[a] = dmin[a], hi[a] = dmax[a];
    }
    if (!(hi[a] > lo[a]))
      throw InputError("domain", std::string("the box is empty along ") + "xyz"[a] + " in " + name);
  }
  std::array<double, 3> box{};
  for (int a = 0; a < d; ++a) box[a] = hi[a] - lo[a];
  s.box = box;
  if (n_periodic == d) {
    s.boundary = Boundary::periodic;
    // The lattice as LAMMPS's triclinic box: a along x, b in the xy plane.
    const auto& px = period[0]->vec;
    const auto& py = period[1]->vec;
    if (px[1] != 0 || px[2] != 0 || py[2] != 0)
      throw InputError("Boundaries", name + ": a periodic shift that tilts x or moves y's images along z; "
                                            "hgridlab's tilted boxes lean y's images along x, z's along x and y");
    // Reduced into LAMMPS's limits (the same lattice): b -= round(xy/lx) a,
    // then c -= round(yz/ly) b, then c -= round(xz/lx) a.
    double xy = py[0], xz = d == 3 ? period[2]->vec[0] : 0.0, yz = d == 3 ? period[2]->vec[1] : 0.0;
    xy -= box[0] * std::nearbyint(xy / box[0]);
    if (d == 3) {
      const double k = std::nearbyint(yz / box[1]);
      yz -= k * box[1];
      xz -= k * xy;
      xz -= box[0] * std::nearbyint(xz / box[0]);
    }
    s.tilt = {xy, xz, yz};
  } else if (n_periodic == 0) {
    s.boundary = Boundary::walls;
  } else {
    s.mixed_boundary = true;
  }
  for (std::size_t i = 0; i < s.radii.size(); ++i)
    for (int a = 0; a < d; ++a) s.positions[i * d + a] -= lo[a];
  return s;
}

}  // namespace hgrid::detail
