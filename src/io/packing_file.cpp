// Packing files: HDF5 (read and write) and CSV (read).

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/h5.hpp"
#include "grid/error.hpp"
#include "io/packing_file.hpp"
#include "io/provenance.hpp"

namespace hgrid {

namespace {

// ---- HDF5 ------------------------------------------------------------------

using namespace detail;

herr_t collect_attr(hid_t loc, const char* name, const H5A_info_t*, void* data) {
  auto* p = static_cast<Packing*>(data);
  const std::string n = name;
  if (n == "d" || n == "box" || n == "boundary") return 0;
  H5Handle a{H5Aopen(loc, name, H5P_DEFAULT), H5Aclose};
  H5Handle t{H5Aget_type(a.id), H5Tclose};
  try {
    if (H5Tget_class(t.id) == H5T_STRING) {
      p->str_attrs[n] = h5_read_string_attr(loc, name, "");
    } else if (H5Tget_class(t.id) == H5T_FLOAT || H5Tget_class(t.id) == H5T_INTEGER) {
      const auto v = h5_read_double_attr(loc, name, "");
      if (v.size() == 1) p->num_attrs[n] = v[0];
    }
  } catch (const InputError&) {
  }
  return 0;
}

Packing read_h5(const std::string& path) {
  std::lock_guard<std::recursive_mutex> lock(h5_mutex());
  h5_silence();
  if (H5Fis_hdf5(path.c_str()) <= 0) throw InputError("file", "'" + path + "' is not a readable HDF5 file");
  H5Handle f{H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  if (f.id < 0) throw InputError("file", "'" + path + "' could not be opened as HDF5 (truncated or corrupt?)");
  H5Handle root{H5Gopen2(f.id, "/", H5P_DEFAULT), H5Gclose};
  Packing p;
  const auto dv = h5_read_double_attr(root.id, "d", path);
  if (dv.size() != 1) throw InputError("d", "attribute must be one number in " + path);
  p.d = static_cast<int>(dv[0]);
  if (p.d != 2 && p.d != 3) throw InputError("d", "must be 2 or 3 (got " + std::to_string(dv[0]) + ")");
  const auto box = h5_read_double_attr(root.id, "box", path);
  if (box.size() != static_cast<std::size_t>(p.d))
    throw InputError("box", "attribute must have d = " + std::to_string(p.d) + " values in " + path);
  for (int a = 0; a < p.d; ++a) p.box[a] = box[a];
  p.boundary = parse_boundary(h5_read_string_attr(root.id, "boundary", path));
  std::vector<hsize_t> dims;
  p.positions = h5_read_dataset(f.id, "/positions", dims, path);
  if (dims.size() != 2 || dims[1] != static_cast<hsize_t>(p.d))
    throw InputError("positions", "dataset must be N x " + std::to_string(p.d) + " in " + path);
  const hsize_t n = dims[0];
  p.radii = h5_read_dataset(f.id, "/radii", dims, path);
  if (dims.size() != 1 || dims[0] != n)
    throw InputError("radii", "dataset must have N = " + std::to_string(n) + " values in " + path);
  H5Aiterate2(root.id, H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, collect_attr, &p);
  return p;
}

// ---- CSV -------------------------------------------------------------------

Packing read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("file", "cannot open '" + path + "'");
  Packing p;
  bool have_box = false, have_header = false;
  std::string line;
  std::size_t lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    const std::string where = path + ":" + std::to_string(lineno);
    if (line[0] == '#') {
      std::istringstream ss(line.substr(1));
      std::string key;
      ss >> key;
      if (key == "box") {
        std::vector<double> b;
        double v;
        while (ss >> v) b.push_back(v);
        if (b.size() != 2 && b.size() != 3) throw InputError("box", "'# box' needs 2 or 3 side lengths at " + where);
        for (std::size_t a = 0; a < b.size(); ++a) p.box[a] = b[a];
        p.d = static_cast<int>(b.size());
        have_box = true;
      } else if (key == "boundary") {
        std::string b;
        ss >> b;
        p.boundary = parse_boundary(b);
      }
      continue;
    }
    if (!have_header) {
      std::string h;
      for (char c : line)
        if (c != ' ' && c != '\t') h += c;
      int d = h == "x,y,r" ? 2 : h == "x,y,z,r" ? 3 : 0;
      if (d == 0) throw InputError("header", "expected 'x,y,r' or 'x,y,z,r' at " + where);
      if (!have_box) throw InputError("box", "a '# box A1 A2 [A3]' line must come before the header in " + path);
      if (d != p.d) throw InputError("box", "'# box' has " + std::to_string(p.d) + " sides but the header is " + h);
      have_header = true;
      continue;
    }
    std::istringstream ss(line);
    std::string cell;
    std::vector<double> vals;
    while (std::getline(ss, cell, ',')) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      while (end && (*end == ' ' || *end == '\t')) ++end;
      if (end == cell.c_str() || (end && *end != '\0')) throw InputError("value", "'" + cell + "' is not a number at " + where);
      vals.push_back(v);
    }
    if (vals.size() != static_cast<std::size_t>(p.d + 1))
      throw InputError("row", "expected " + std::to_string(p.d + 1) + " values at " + where);
    for (int a = 0; a < p.d; ++a) p.positions.push_back(vals[a]);
    p.radii.push_back(vals[p.d]);
  }
  if (!have_header) throw InputError("header", "no 'x,y,r' or 'x,y,z,r' header in " + path);
  return p;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

Packing read_packing(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError("file", "'" + path + "' does not exist");
  Packing p = ends_with(path, ".csv") ? read_csv(path) : read_h5(path);
  validate(p);
  return p;
}

void write_packing(const std::string& path, const Packing& p) {
  detail::h5_write_file(path, [&](hid_t f) {
    const hsize_t n = p.size();
    detail::h5_write_dataset(f, "/positions", p.positions, {n, static_cast<hsize_t>(p.d)});
    detail::h5_write_dataset(f, "/radii", p.radii, {n});
    detail::H5Handle root{H5Gopen2(f, "/", H5P_DEFAULT), H5Gclose};
    detail::h5_write_attr(root.id, "d", std::vector<double>{static_cast<double>(p.d)});
    detail::h5_write_attr(root.id, "box", std::vector<double>(p.box.begin(), p.box.begin() + p.d));
    detail::h5_write_attr(root.id, "boundary", std::string(to_string(p.boundary)));
    for (const auto& [k, v] : p.num_attrs) detail::h5_write_attr(root.id, k, std::vector<double>{v});
    for (const auto& [k, v] : p.str_attrs) detail::h5_write_attr(root.id, k, v);
    if (!p.str_attrs.count("git_hash")) detail::h5_write_attr(root.id, "git_hash", std::string(git_hash()));
    if (!p.str_attrs.count("compiler")) detail::h5_write_attr(root.id, "compiler", std::string(compiler_id()));
  });
}

}  // namespace hgrid
