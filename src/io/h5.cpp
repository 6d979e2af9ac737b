#include "hgridlab/io/h5.hpp"

#include <cstring>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/atomic_file.hpp"

namespace hgrid::detail {

std::recursive_mutex& h5_mutex() {
  static std::recursive_mutex m;
  return m;
}

void h5_silence() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

std::vector<double> h5_read_double_attr(hid_t obj, const char* name, const std::string& file) {
  H5Handle a{H5Aopen(obj, name, H5P_DEFAULT), H5Aclose};
  if (a.id < 0) throw InputError(name, "attribute missing in " + file);
  H5Handle t{H5Aget_type(a.id), H5Tclose};
  const H5T_class_t cls = H5Tget_class(t.id);
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) throw InputError(name, "attribute is not numeric in " + file);
  H5Handle sp{H5Aget_space(a.id), H5Sclose};
  const hssize_t n = H5Sget_simple_extent_npoints(sp.id);
  if (n < 0 || n > static_cast<hssize_t>(kMaxNumericAttrValues))
    throw InputError(name, "attribute of unusable size in " + file);
  std::vector<double> v(n > 0 ? n : 0);
  if (n > 0 && H5Aread(a.id, H5T_NATIVE_DOUBLE, v.data()) < 0)
    throw InputError(name, "attribute is not numeric in " + file);
  return v;
}

std::string h5_read_string_attr(hid_t obj, const char* name, const std::string& file) {
  H5Handle a{H5Aopen(obj, name, H5P_DEFAULT), H5Aclose};
  if (a.id < 0) throw InputError(name, "attribute missing in " + file);
  H5Handle t{H5Aget_type(a.id), H5Tclose};
  if (H5Tget_class(t.id) != H5T_STRING) throw InputError(name, "attribute is not a string in " + file);
  H5Handle sp{H5Aget_space(a.id), H5Sclose};
  if (H5Sget_simple_extent_npoints(sp.id) != 1) throw InputError(name, "attribute must be one string in " + file);
  // The memory type takes the file's character set (h5py writes UTF-8), so
  // that no conversion is asked for.
  H5Handle mt{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_cset(mt.id, H5Tget_cset(t.id));
  if (H5Tis_variable_str(t.id) > 0) {
    H5Tset_size(mt.id, H5T_VARIABLE);
    char* buf = nullptr;
    if (H5Aread(a.id, mt.id, &buf) < 0) throw InputError(name, "unreadable attribute in " + file);
    std::string s = buf ? buf : "";
    H5free_memory(buf);
    return s;
  }
  // Fixed length: read with null padding into one byte more than the size,
  // so that a string filling its whole width (no terminator, as h5py and
  // numpy write them) keeps its last character.
  const std::size_t size = H5Tget_size(t.id);
  if (size == 0 || size > kMaxStringAttrBytes) throw InputError(name, "string attribute of unusable size in " + file);
  std::string s(size + 1, '\0');
  H5Tset_size(mt.id, size);
  H5Tset_strpad(mt.id, H5T_STR_NULLPAD);
  if (H5Aread(a.id, mt.id, s.data()) < 0) throw InputError(name, "unreadable attribute in " + file);
  s.resize(std::strlen(s.c_str()));
  return s;
}

std::vector<double> h5_read_rows(hid_t file, const char* name, hsize_t first, hsize_t count, int cols,
                                 const std::string& path) {
  H5Handle ds{H5Dopen2(file, name, H5P_DEFAULT), H5Dclose};
  if (ds.id < 0) throw InputError(name, "dataset missing in " + path);
  H5Handle t{H5Dget_type(ds.id), H5Tclose};
  const H5T_class_t cls = H5Tget_class(t.id);
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) throw InputError(name, "dataset is not numeric in " + path);
  std::vector<double> out(count * static_cast<hsize_t>(cols));
  if (count == 0) return out;
  H5Handle file_space{H5Dget_space(ds.id), H5Sclose};
  const hsize_t start[2] = {first, 0}, size[2] = {count, static_cast<hsize_t>(cols)};
  const int rank = cols == 1 ? 1 : 2;
  if (H5Sselect_hyperslab(file_space.id, H5S_SELECT_SET, start, nullptr, size, nullptr) < 0)
    throw InputError(name, "rows " + std::to_string(first) + " to " + std::to_string(first + count) +
                               " are not in the dataset of " + path);
  H5Handle mem_space{H5Screate_simple(rank, size, nullptr), H5Sclose};
  if (H5Dread(ds.id, H5T_NATIVE_DOUBLE, mem_space.id, file_space.id, H5P_DEFAULT, out.data()) < 0)
    throw InputError(name, "could not read dataset (truncated or corrupt file?) in " + path);
  return out;
}

void h5_write_attr(hid_t obj, const std::string& name, const std::vector<double>& v) {
  const hsize_t n = v.size();
  H5Handle sp{n == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose};
  H5Handle a{H5Acreate2(obj, name.c_str(), H5T_NATIVE_DOUBLE, sp.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  if (a.id < 0 || H5Awrite(a.id, H5T_NATIVE_DOUBLE, v.data()) < 0)
    throw std::runtime_error("HDF5: cannot write attribute " + name);
}

void h5_write_attr(hid_t obj, const std::string& name, const std::string& v) {
  // Variable-length UTF-8, as h5py writes str (and reads it back as str).
  H5Handle t{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(t.id, H5T_VARIABLE);
  H5Tset_cset(t.id, H5T_CSET_UTF8);
  H5Handle sp{H5Screate(H5S_SCALAR), H5Sclose};
  H5Handle a{H5Acreate2(obj, name.c_str(), t.id, sp.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  const char* text = v.c_str();
  if (a.id < 0 || H5Awrite(a.id, t.id, &text) < 0) throw std::runtime_error("HDF5: cannot write attribute " + name);
}

void h5_write_attr(hid_t obj, const std::string& name, std::int64_t v) {
  H5Handle sp{H5Screate(H5S_SCALAR), H5Sclose};
  H5Handle a{H5Acreate2(obj, name.c_str(), H5T_STD_I64LE, sp.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  if (a.id < 0 || H5Awrite(a.id, H5T_NATIVE_INT64, &v) < 0) throw std::runtime_error("HDF5: cannot write attribute " + name);
}

bool h5_has_attr(hid_t obj, const char* name) { return H5Aexists_by_name(obj, ".", name, H5P_DEFAULT) > 0; }

namespace {
/// Dataset creation without modification times, so that the same content
/// gives the same file bit for bit.
hid_t untimed_dcpl() {
  const hid_t p = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_obj_track_times(p, false);
  return p;
}

template <class T>
void write_numeric(hid_t file, const std::string& name, const std::vector<T>& v, std::vector<hsize_t> dims,
                   hid_t file_type, hid_t mem_type) {
  H5Handle sp{H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose};
  const H5Handle dcpl{untimed_dcpl(), H5Pclose};
  H5Handle ds{H5Dcreate2(file, name.c_str(), file_type, sp.id, H5P_DEFAULT, dcpl.id, H5P_DEFAULT), H5Dclose};
  if (ds.id < 0 || (!v.empty() && H5Dwrite(ds.id, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0))
    throw std::runtime_error("HDF5: cannot write dataset " + name);
}
}  // namespace

void h5_write_dataset(hid_t file, const std::string& name, const std::vector<double>& v, std::vector<hsize_t> dims) {
  write_numeric(file, name, v, std::move(dims), H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
}

void h5_write_dataset(hid_t file, const std::string& name, const std::vector<std::uint64_t>& v,
                      std::vector<hsize_t> dims) {
  write_numeric(file, name, v, std::move(dims), H5T_STD_U64LE, H5T_NATIVE_UINT64);
}

void h5_write_strings(hid_t file, const std::string& name, const std::vector<std::string>& v) {
  std::size_t width = 1;
  for (const auto& s : v) width = std::max(width, s.size());
  std::vector<char> buf(width * v.size(), '\0');
  for (std::size_t i = 0; i < v.size(); ++i) std::memcpy(buf.data() + i * width, v[i].data(), v[i].size());
  H5Handle t{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(t.id, width);
  const hsize_t n = v.size();
  H5Handle sp{H5Screate_simple(1, &n, nullptr), H5Sclose};
  const H5Handle dcpl{untimed_dcpl(), H5Pclose};
  H5Handle ds{H5Dcreate2(file, name.c_str(), t.id, sp.id, H5P_DEFAULT, dcpl.id, H5P_DEFAULT), H5Dclose};
  if (ds.id < 0 || (n > 0 && H5Dwrite(ds.id, t.id, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0))
    throw std::runtime_error("HDF5: cannot write dataset " + name);
}

void h5_write_file(const std::string& path, const std::function<void(hid_t file)>& fill) {
  std::lock_guard<std::recursive_mutex> lock(h5_mutex());
  h5_silence();
  write_file_atomically(path, [&](const std::string& tmp) {
    H5Handle fcpl{H5Pcreate(H5P_FILE_CREATE), H5Pclose};
    H5Pset_obj_track_times(fcpl.id, false);  // root group: no time stamps either
    H5Handle f{H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, fcpl.id, H5P_DEFAULT), H5Fclose};
    if (f.id < 0) throw InputError("out", "cannot create '" + tmp + "'");
    fill(f.id);
    if (H5Fflush(f.id, H5F_SCOPE_GLOBAL) < 0) throw InputError("out", "HDF5 write failed for '" + path + "' (disk full?)");
  });
}

}  // namespace hgrid::detail
