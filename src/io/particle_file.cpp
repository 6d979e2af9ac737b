// Particle files of every supported format: detection and the common type.
#include "hgridlab/io/particle_file.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/detail/lammps_reader.hpp"
#include "hgridlab/io/detail/mercury_reader.hpp"
#include "hgridlab/io/detail/table_reader.hpp"
#include "hgridlab/io/detail/text_lines.hpp"

namespace hgrid {
namespace {

/// Bytes looked at for a NUL (a binary file that is not HDF5).
constexpr std::size_t kBinaryProbeBytes = 4096;

}  // namespace

bool hdf5_file(const std::string& path) {
  const auto ext = std::filesystem::path(path).extension().string();
  if (ext == ".h5" || ext == ".hdf5" || ext == ".hdf") return true;
  char magic[8] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(magic, sizeof magic);
  return in.gcount() == 8 && std::string_view(magic, 8) == "\x89HDF\r\n\x1a\n";
}

namespace {

ParticleSet from_packing(Packing p) {
  ParticleSet s;
  s.format = ParticleFormat::hdf5;
  s.d = p.d;
  s.radii = std::move(p.radii);
  s.positions = std::move(p.positions);
  s.box = p.box;
  s.tilt = p.tilt;
  s.boundary = p.boundary;
  return s;
}

}  // namespace

const char* to_string(ParticleFormat f) {
  switch (f) {
    case ParticleFormat::hdf5: return "hdf5";
    case ParticleFormat::table: return "table";
    case ParticleFormat::lammps_data: return "lammps_data";
    case ParticleFormat::lammps_dump: return "lammps_dump";
    case ParticleFormat::mercury_data: return "mercury_data";
    case ParticleFormat::mercury_restart: return "mercury_restart";
  }
  return "?";
}

double ParticleSet::packing_fraction() const {
  if (!box || (d != 2 && d != 3)) throw InputError("nu", "the packing fraction needs a box and d");
  double vol = 0;
  for (double r : radii) vol += ball_volume(d, r);
  double box_vol = 1;
  for (int a = 0; a < d; ++a) box_vol *= (*box)[a];
  return vol / box_vol;
}

ParticleSet parse_particles(std::string_view text, const std::string& name, std::optional<std::int64_t> frame) {
  if (text.substr(0, kBinaryProbeBytes).find('\0') != std::string_view::npos)
    throw InputError("file", name + " is binary and not HDF5; expected " + kParticleFormats);
  detail::Lines at(text, name);
  std::string_view line;
  while (at.next(line) && detail::blank(line)) {
  }
  if (detail::trim(line).substr(0, 5) == "ITEM:") return detail::parse_lammps_dump(text, name, frame);
  if (detail::looks_like_mercury_data(text)) return detail::parse_mercury_data(text, name, frame);
  detail::resolve_frame(frame, 1, name);  // one snapshot
  if (detail::looks_like_mercury_restart(text)) return detail::parse_mercury_restart(text, name);
  if (detail::looks_like_lammps_data(text)) return detail::parse_lammps_data(text, name);
  return detail::parse_table(text, name);
}

ParticleSet read_particles(const std::string& path, Isolation isolation, std::optional<std::int64_t> frame) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError("file", "'" + path + "' does not exist");
  if (std::filesystem::is_directory(path, ec)) throw InputError("file", "'" + path + "' is a directory");
  if (hdf5_file(path)) {
    detail::resolve_frame(frame, 1, path);  // one snapshot
    return from_packing(read_hdf5_packing(path, isolation));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("file", "cannot open '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError("file", "cannot read '" + path + "'");
  return parse_particles(text.str(), path, frame);
}

Packing to_packing(ParticleSet s, const std::string& name) {
  if (!s.box)
    throw InputError("box", name + " has no box: add a '# box A1 A2 [A3]' line (side lengths, origin at 0)");
  if (!s.has_positions()) throw InputError("positions", name + " has radii only; the grids need x, y[, z] columns too");
  if (s.mixed_boundary)
    throw InputError("boundary", name + " has periodic and non-periodic axes; hgridlab's grids need one boundary");
  Packing p;
  p.d = s.d;
  p.box = *s.box;
  p.tilt = s.tilt;
  p.boundary = s.boundary.value_or(Boundary::periodic);
  if (!s.boundary) p.str_attrs[kBoundarySourceAttr] = kBoundaryAssumed;
  p.positions = std::move(s.positions);
  p.radii = std::move(s.radii);
  validate(p);
  return p;
}

std::string boundary_description(const Packing& p) {
  const auto it = p.str_attrs.find(kBoundarySourceAttr);
  std::string out = it != p.str_attrs.end() && it->second == kBoundaryAssumed ? "periodic (not in the file: assumed)"
                                                                                : to_string(p.boundary);
  if (p.tilted())
    out += p.d == 2 ? ", tilted box xy = " + format_number(p.tilt[0])
                    : ", tilted box xy xz yz = " + format_number(p.tilt[0]) + " " + format_number(p.tilt[1]) + " " +
                          format_number(p.tilt[2]);
  return out;
}

std::string boundary_description(const ParticleSet& s) {
  if (s.mixed_boundary) return "mixed (periodic and not)";
  if (!s.boundary) return "periodic (not in the file: assumed)";
  return to_string(*s.boundary);
}

void check_file_dimension(int file_d, std::optional<int> d, const std::string& file) {
  if (!d) return;
  if (*d != 2 && *d != 3) throw InputError("d", "must be 2 or 3 (got " + std::to_string(*d) + ")");
  if (file_d != *d)
    throw InputError("d", "--d " + std::to_string(*d) + " disagrees with " + file + ", which is " +
                              std::to_string(file_d) + "D (a LAMMPS file is 2D when all its z are equal)");
}

FileInputs file_inputs(const ParticleSet& s, const std::string& file, std::optional<int> d, std::optional<double> nu) {
  FileInputs in;
  if (d) {
    if (*d != 2 && *d != 3) throw InputError("d", "must be 2 or 3 (got " + std::to_string(*d) + ")");
    if (s.d == 2 || s.d == 3) check_file_dimension(s.d, d, file);
    in.d = *d;
  } else if (s.d == 2 || s.d == 3) {
    in.d = s.d;
  } else {
    throw InputError("d", file + " holds radii only: give --d 2 or --d 3");
  }
  if (nu) {
    if (!(std::isfinite(*nu) && *nu > 0)) throw InputError("nu", "must be a finite number > 0 (got " + format_number(*nu) + ")");
    in.nu = *nu;
  } else if (s.box && s.d == in.d) {
    in.nu = s.packing_fraction();
    in.nu_from_box = true;
  } else {
    throw InputError("nu", file + " has no box: give --nu, the packing fraction of your system (e.g. --nu 0.6)");
  }
  return in;
}

}  // namespace hgrid
