// Packing files: HDF5 (read and write) and CSV (read).
#include <hdf5.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "hgrid/error.hpp"
#include "hgrid/packing.hpp"

namespace hgrid {

const char* git_hash() { return HGRID_GIT_HASH; }
const char* compiler_id() { return HGRID_COMPILER; }

double Packing::packing_fraction() const {
  double vol = 0;
  const double vd = d == 2 ? M_PI : 4.0 * M_PI / 3.0;
  for (double r : radii) vol += vd * (d == 2 ? r * r : r * r * r);
  double box_vol = 1;
  for (int a = 0; a < d; ++a) box_vol *= box[a];
  return vol / box_vol;
}

void validate(Packing& p) {
  if (p.d != 2 && p.d != 3) throw InputError("d", "must be 2 or 3 (got " + std::to_string(p.d) + ")");
  for (int a = 0; a < p.d; ++a)
    if (!(std::isfinite(p.box[a]) && p.box[a] > 0))
      throw InputError("box", "side " + std::to_string(a + 1) + " must be finite and > 0");
  if (p.positions.size() != p.radii.size() * static_cast<std::size_t>(p.d))
    throw InputError("positions", "expected " + std::to_string(p.radii.size()) + " x " + std::to_string(p.d) +
                                      " values, got " + std::to_string(p.positions.size()));
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!(std::isfinite(p.radii[i]) && p.radii[i] > 0))
      throw InputError("radius", "particle " + std::to_string(i) + " has radius " + std::to_string(p.radii[i]) +
                                     " (must be finite and > 0)");
    for (int a = 0; a < p.d; ++a) {
      double& x = p.positions[i * p.d + a];
      if (!std::isfinite(x))
        throw InputError("position", "particle " + std::to_string(i) + " has a non-finite coordinate");
      if (p.boundary == Boundary::periodic) {
        x = detail::wrap(x, p.box[a]);
      } else if (x < 0 || x > p.box[a]) {
        throw InputError("position", "particle " + std::to_string(i) + " has its centre outside the walled box [0, " +
                                         std::to_string(p.box[a]) + "] on axis " + std::to_string(a + 1));
      }
    }
  }
}

Boundary parse_boundary(const std::string& s) {
  if (s == "periodic") return Boundary::periodic;
  if (s == "walls") return Boundary::walls;
  throw InputError("boundary", "must be 'periodic' or 'walls' (got '" + s + "')");
}

namespace {

// ---- HDF5 ------------------------------------------------------------------

/// Closes an HDF5 handle when it goes out of scope.
struct H5Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  ~H5Handle() {
    if (id >= 0) close(id);
  }
};

void silence_hdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

std::vector<double> read_double_attr(hid_t obj, const char* name, const std::string& file) {
  H5Handle a{H5Aopen(obj, name, H5P_DEFAULT), H5Aclose};
  if (a.id < 0) throw InputError(name, "attribute missing in " + file);
  H5Handle sp{H5Aget_space(a.id), H5Sclose};
  const hssize_t n = H5Sget_simple_extent_npoints(sp.id);
  std::vector<double> v(n > 0 ? n : 0);
  if (n > 0 && H5Aread(a.id, H5T_NATIVE_DOUBLE, v.data()) < 0)
    throw InputError(name, "attribute is not numeric in " + file);
  return v;
}

std::string read_string_attr(hid_t obj, const char* name, const std::string& file) {
  H5Handle a{H5Aopen(obj, name, H5P_DEFAULT), H5Aclose};
  if (a.id < 0) throw InputError(name, "attribute missing in " + file);
  H5Handle t{H5Aget_type(a.id), H5Tclose};
  if (H5Tget_class(t.id) != H5T_STRING) throw InputError(name, "attribute is not a string in " + file);
  if (H5Tis_variable_str(t.id) > 0) {
    H5Handle mt{H5Tcopy(H5T_C_S1), H5Tclose};
    H5Tset_size(mt.id, H5T_VARIABLE);
    char* buf = nullptr;
    if (H5Aread(a.id, mt.id, &buf) < 0) throw InputError(name, "unreadable attribute in " + file);
    std::string s = buf ? buf : "";
    H5free_memory(buf);
    return s;
  }
  const std::size_t size = H5Tget_size(t.id);
  std::string s(size, '\0');
  H5Handle mt{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(mt.id, size);
  if (H5Aread(a.id, mt.id, s.data()) < 0) throw InputError(name, "unreadable attribute in " + file);
  s.resize(std::strlen(s.c_str()));
  return s;
}

std::vector<double> read_dataset(hid_t file, const char* name, std::vector<hsize_t>& dims, const std::string& path) {
  H5Handle ds{H5Dopen2(file, name, H5P_DEFAULT), H5Dclose};
  if (ds.id < 0) throw InputError(name, "dataset missing in " + path);
  H5Handle sp{H5Dget_space(ds.id), H5Sclose};
  const int rank = H5Sget_simple_extent_ndims(sp.id);
  if (rank < 1 || rank > 2) throw InputError(name, "dataset must have rank 1 or 2 in " + path);
  dims.assign(rank, 0);
  H5Sget_simple_extent_dims(sp.id, dims.data(), nullptr);
  hsize_t n = 1;
  for (auto v : dims) n *= v;
  std::vector<double> out(n);
  if (n > 0 && H5Dread(ds.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw InputError(name, "could not read dataset (truncated or corrupt file?) in " + path);
  return out;
}

herr_t collect_attr(hid_t loc, const char* name, const H5A_info_t*, void* data) {
  auto* p = static_cast<Packing*>(data);
  const std::string n = name;
  if (n == "d" || n == "box" || n == "boundary") return 0;
  H5Handle a{H5Aopen(loc, name, H5P_DEFAULT), H5Aclose};
  H5Handle t{H5Aget_type(a.id), H5Tclose};
  try {
    if (H5Tget_class(t.id) == H5T_STRING) {
      p->str_attrs[n] = read_string_attr(loc, name, "");
    } else if (H5Tget_class(t.id) == H5T_FLOAT || H5Tget_class(t.id) == H5T_INTEGER) {
      const auto v = read_double_attr(loc, name, "");
      if (v.size() == 1) p->num_attrs[n] = v[0];
    }
  } catch (const InputError&) {
  }
  return 0;
}

Packing read_h5(const std::string& path) {
  silence_hdf5();
  if (H5Fis_hdf5(path.c_str()) <= 0) throw InputError("file", "'" + path + "' is not a readable HDF5 file");
  H5Handle f{H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  if (f.id < 0) throw InputError("file", "'" + path + "' could not be opened as HDF5 (truncated or corrupt?)");
  H5Handle root{H5Gopen2(f.id, "/", H5P_DEFAULT), H5Gclose};
  Packing p;
  const auto dv = read_double_attr(root.id, "d", path);
  if (dv.size() != 1) throw InputError("d", "attribute must be one number in " + path);
  p.d = static_cast<int>(dv[0]);
  if (p.d != 2 && p.d != 3) throw InputError("d", "must be 2 or 3 (got " + std::to_string(dv[0]) + ")");
  const auto box = read_double_attr(root.id, "box", path);
  if (box.size() != static_cast<std::size_t>(p.d))
    throw InputError("box", "attribute must have d = " + std::to_string(p.d) + " values in " + path);
  for (int a = 0; a < p.d; ++a) p.box[a] = box[a];
  p.boundary = parse_boundary(read_string_attr(root.id, "boundary", path));
  std::vector<hsize_t> dims;
  p.positions = read_dataset(f.id, "/positions", dims, path);
  if (dims.size() != 2 || dims[1] != static_cast<hsize_t>(p.d))
    throw InputError("positions", "dataset must be N x " + std::to_string(p.d) + " in " + path);
  const hsize_t n = dims[0];
  p.radii = read_dataset(f.id, "/radii", dims, path);
  if (dims.size() != 1 || dims[0] != n)
    throw InputError("radii", "dataset must have N = " + std::to_string(n) + " values in " + path);
  H5Aiterate2(root.id, H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, collect_attr, &p);
  return p;
}

void write_attr(hid_t obj, const std::string& name, const std::vector<double>& v) {
  const hsize_t n = v.size();
  H5Handle sp{n == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose};
  H5Handle a{H5Acreate2(obj, name.c_str(), H5T_NATIVE_DOUBLE, sp.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  if (a.id < 0 || H5Awrite(a.id, H5T_NATIVE_DOUBLE, v.data()) < 0)
    throw std::runtime_error("HDF5: cannot write attribute " + name);
}

void write_attr(hid_t obj, const std::string& name, const std::string& v) {
  H5Handle t{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(t.id, v.empty() ? 1 : v.size());
  H5Handle sp{H5Screate(H5S_SCALAR), H5Sclose};
  H5Handle a{H5Acreate2(obj, name.c_str(), t.id, sp.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  if (a.id < 0 || H5Awrite(a.id, t.id, v.c_str()) < 0) throw std::runtime_error("HDF5: cannot write attribute " + name);
}

void write_dataset(hid_t file, const char* name, const std::vector<double>& v, std::vector<hsize_t> dims) {
  H5Handle sp{H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose};
  H5Handle ds{H5Dcreate2(file, name, H5T_IEEE_F64LE, sp.id, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose};
  if (ds.id < 0 || (!v.empty() && H5Dwrite(ds.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0))
    throw std::runtime_error(std::string("HDF5: cannot write dataset ") + name);
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
  silence_hdf5();
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  try {
    H5Handle f{H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose};
    if (f.id < 0) throw InputError("out", "cannot create '" + tmp + "'");
    const hsize_t n = p.size();
    write_dataset(f.id, "/positions", p.positions, {n, static_cast<hsize_t>(p.d)});
    write_dataset(f.id, "/radii", p.radii, {n});
    H5Handle root{H5Gopen2(f.id, "/", H5P_DEFAULT), H5Gclose};
    write_attr(root.id, "d", std::vector<double>{static_cast<double>(p.d)});
    write_attr(root.id, "box", std::vector<double>(p.box.begin(), p.box.begin() + p.d));
    write_attr(root.id, "boundary", std::string(to_string(p.boundary)));
    for (const auto& [k, v] : p.num_attrs) write_attr(root.id, k, std::vector<double>{v});
    for (const auto& [k, v] : p.str_attrs) write_attr(root.id, k, v);
    if (!p.str_attrs.count("git_hash")) write_attr(root.id, "git_hash", std::string(git_hash()));
    if (!p.str_attrs.count("compiler")) write_attr(root.id, "compiler", std::string(compiler_id()));
    if (H5Fflush(f.id, H5F_SCOPE_GLOBAL) < 0) throw std::runtime_error("HDF5: flush failed for " + tmp);
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace hgrid
