// Small HDF5 helpers shared by packing and result files (HDF5 C API).
#pragma once
#include <hdf5.h>

#include <functional>
#include <cstdint>
#include <stdexcept>
#include <mutex>
#include <string>
#include <vector>

#include "hgridlab/base/error.hpp"

namespace hgrid::detail {

/// Debian's HDF5 is built without thread safety: every use holds this lock.
std::recursive_mutex& h5_mutex();

/// Closes an HDF5 handle when it goes out of scope.
struct H5Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  H5Handle(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {}
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  ~H5Handle() {
    if (id >= 0) close(id);
  }
};

/// Turns off HDF5's own error printing; errors are reported by the caller.
void h5_silence();

std::vector<double> h5_read_double_attr(hid_t obj, const char* name, const std::string& file);
std::string h5_read_string_attr(hid_t obj, const char* name, const std::string& file);
/// Rows [first, first + count) of a numeric dataset of `cols` columns (rank
/// 1 when cols is 1, else N x cols; checked by the caller) as doubles.
std::vector<double> h5_read_rows(hid_t file, const char* name, hsize_t first, hsize_t count, int cols,
                                 const std::string& path);

/// Whether obj has an attribute of that name (no attribute is iterated).
bool h5_has_attr(hid_t obj, const char* name);

/// Limits on what a file may declare before it is read.
inline constexpr std::size_t kMaxStringAttrBytes = 1 << 20;
inline constexpr std::size_t kMaxNumericAttrValues = 1 << 16;

void h5_write_attr(hid_t obj, const std::string& name, const std::vector<double>& v);
void h5_write_attr(hid_t obj, const std::string& name, const std::string& v);
/// An integer attribute (h5py reads it as an int).
void h5_write_attr(hid_t obj, const std::string& name, std::int64_t v);
void h5_write_dataset(hid_t file, const std::string& name, const std::vector<double>& v, std::vector<hsize_t> dims);
void h5_write_dataset(hid_t file, const std::string& name, const std::vector<std::uint64_t>& v,
                      std::vector<hsize_t> dims);
void h5_write_strings(hid_t file, const std::string& name, const std::vector<std::string>& v);

/// Creates `path` through a temporary file: fill(file_id) writes the content,
/// then the file is closed and renamed onto `path`. Nothing is left at `path`
/// (or at the temporary name) if fill throws.
void h5_write_file(const std::string& path, const std::function<void(hid_t file)>& fill);

}  // namespace hgrid::detail
