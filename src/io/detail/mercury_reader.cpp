#include "hgridlab/io/detail/mercury_reader.hpp"

#include <array>
#include <cmath>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/detail/text_lines.hpp"

namespace hgrid::detail {
namespace {

/// All tokens numbers?
bool numeric(const std::vector<std::string_view>& toks) {
  double v;
  for (auto t : toks)
    if (!to_number(t, v)) return false;
  return true;
}

/// Values of a particle line after a header of `header` tokens (6: 2D, 8: 3D).
std::size_t particle_values(std::size_t header) { return header == 6 ? 8 : 14; }

struct Snapshot {
  std::size_t line = 0;   // the header's line number
  std::size_t n = 0;
};

}  // namespace

bool looks_like_mercury_data(std::string_view text) {
  Lines at(text, "");
  std::string_view line;
  while (at.next(line) && blank(line)) {
  }
  const auto head = split_ws(line);
  if ((head.size() != 6 && head.size() != 8) || !numeric(head)) return false;
  double n;
  to_number(head[0], n);
  if (!(n >= 0 && n <= 9e15 && n == std::floor(n))) return false;  // a whole count (no cast out of range)
  while (at.next(line)) {
    if (blank(line)) continue;
    const auto next = split_ws(line);
    if (!numeric(next)) return false;
    return n > 0 ? next.size() == particle_values(head.size()) : next.size() == 6 || next.size() == 8;
  }
  return true;  // one header, no particles
}

ParticleSet parse_mercury_data(std::string_view text, const std::string& name, std::optional<std::int64_t> frame) {
  // First pass: every snapshot's header and the shape of its lines.
  std::vector<Snapshot> snaps;
  std::size_t header = 0;
  {
    Lines at(text, name);
    std::string_view line;
    std::size_t left = 0;  // particle lines still to come in this snapshot
    while (at.next(line)) {
      if (blank(line)) continue;
      const auto toks = split_ws(line);
      if (left > 0) {
        if (toks.size() != particle_values(header))
          throw InputError("particles", "expected " + std::to_string(particle_values(header)) +
                                            " values (a particle of the snapshot at line " +
                                            std::to_string(snaps.back().line) + ", which declares " +
                                            std::to_string(snaps.back().n) + "), got " + std::to_string(toks.size()) +
                                            " at " + at.where());
        --left;
        continue;
      }
      if (toks.size() != 6 && toks.size() != 8)
        throw InputError("header", "expected a snapshot header 'N t xmin ymin [zmin] xmax ymax [zmax]' at " + at.where());
      if (header != 0 && toks.size() != header)
        throw InputError("header", "a " + std::string(toks.size() == 6 ? "2D" : "3D") + " header in a " +
                                       (header == 6 ? "2D" : "3D") + " file at " + at.where());
      header = toks.size();
      const std::size_t n = count_number(toks[0], "N", at, kMaxParticles);
      for (std::size_t k = 1; k < toks.size(); ++k) finite_number(toks[k], "header", at);
      snaps.push_back({at.number(), n});
      left = n;
    }
    if (left > 0)
      throw InputError("particles", name + " ends " + std::to_string(left) + " particle line" + (left == 1 ? "" : "s") +
                                        " short of the snapshot at line " + std::to_string(snaps.back().line) +
                                        ", which declares " + std::to_string(snaps.back().n));
  }
  if (snaps.empty()) throw InputError("header", name + " holds no snapshot");
  const std::size_t pick = resolve_frame(frame, snaps.size(), name);
  const Snapshot& s = snaps[pick];
  if (s.n == 0)
    throw InputError("frame", "snapshot " + std::to_string(pick) + " of " + name + " (line " + std::to_string(s.line) +
                                  ") holds no particles; choose another with --frame");
  // Second pass: the chosen snapshot.
  ParticleSet out;
  out.format = ParticleFormat::mercury_data;
  out.d = header == 6 ? 2 : 3;
  out.frame = pick;
  out.frames = snaps.size();
  const int d = out.d;
  Lines at(text, name);
  std::string_view line;
  while (at.number() < s.line && at.next(line)) {
  }
  const auto head = split_ws(line);
  std::array<double, 3> lo{}, hi{}, box{};
  for (int a = 0; a < d; ++a) {
    lo[a] = finite_number(head[2 + a], "header", at);
    hi[a] = finite_number(head[2 + d + a], "header", at);
    box[a] = hi[a] - lo[a];
    if (!(box[a] > 0)) throw InputError("header", "the domain's min must be below its max on every axis at " + at.where());
  }
  out.box = box;
  out.radii.reserve(s.n);
  out.positions.reserve(s.n * d);
  const std::size_t radius_at = d == 2 ? 4 : 6;
  for (std::size_t i = 0; i < s.n;) {
    at.next(line);
    if (blank(line)) continue;
    const auto toks = split_ws(line);
    for (int a = 0; a < d; ++a) out.positions.push_back(finite_number(toks[a], std::string(1, "xyz"[a]), at) - lo[a]);
    out.radii.push_back(positive_number(toks[radius_at], "radius", at));
    ++i;
  }
  return out;
}

}  // namespace hgrid::detail
