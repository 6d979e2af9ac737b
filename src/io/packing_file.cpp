// Packing files: HDF5 (read and write); the text formats through io/particle_file.

#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <stdexcept>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "hgridlab/io/h5.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/io/detail/text_lines.hpp"
#include "hgridlab/io/particle_file.hpp"
#include "hgridlab/io/provenance.hpp"

namespace hgrid {

namespace {

// ---- HDF5 ------------------------------------------------------------------

using namespace detail;

/// The root attributes a packing file may carry beyond d, box and boundary
/// (what the generator records, and the provenance). Read by name: a file's
/// other attributes are never iterated, so a corrupt attribute table cannot
/// reach the reader.
const char* const kStringAttrs[] = {"cache_key", "dist", "placement", "seed_str", "method", "git_hash", "compiler", "build_flags",
                                    "version", "equilibration_chain", "equilibration_rng_state",
                                    "stationarity_series", "stationarity_rule", "stationarity_observable"};
const char* const kNumberAttrs[] = {"seed", "n", "nu", "alpha", "omega", "sigma", "equilibrate", "generator_version",
                                    "rcp_estimate", "nu_achieved", "max_rel_overlap", "mean_rel_overlap",
                                    "mean_contacts", "slab_max_dev", "ks_distance", "ks_pvalue", "fire_steps",
                                    "growth_start_nu", "growth_steps", "neighbour_list_builds",
                                    "equilibration_acceptance", "equilibration_swap_acceptance",
                                    "equilibration_sweeps", "equilibration_moves_accepted",
                                    "equilibration_moves_proposed", "equilibration_swaps_accepted",
                                    "equilibration_swaps_proposed", "stationarity_sample_sweeps", "stationarity_rel_tol",
                                    "stationarity_K", "stationarity_mean", "stationarity_drift_per_doubling",
                                    "stationarity_drift_se", "stationarity_samples", "stationarity_reached"};

/// Declared values of a dataset, checked against what the file stores and
/// against the memory available, before anything is allocated.
hsize_t declared_rows(hid_t file, const char* name, int cols, const std::string& path, hsize_t parts = 1) {
  H5Handle ds{H5Dopen2(file, name, H5P_DEFAULT), H5Dclose};
  if (ds.id < 0) throw InputError(name + 1, "dataset missing in " + path);
  H5Handle sp{H5Dget_space(ds.id), H5Sclose};
  const int rank = H5Sget_simple_extent_ndims(sp.id);
  if (rank != (cols == 1 ? 1 : 2))
    throw InputError(name + 1, "dataset must be " + std::string(cols == 1 ? "N" : "N x " + std::to_string(cols)) +
                                   " in " + path);
  hsize_t dims[2] = {0, 0};
  H5Sget_simple_extent_dims(sp.id, dims, nullptr);
  if (rank == 2 && dims[1] != static_cast<hsize_t>(cols))
    throw InputError(name + 1, "dataset must be N x " + std::to_string(cols) + " in " + path);
  check_memory(name + 1, (dims[0] + parts - 1) / parts, kReadBytesPerParticle, "reading a packing");
  // Without filters (compression) a dataset stores every value it declares:
  // a smaller storage is a truncated or forged file.
  H5Handle dcpl{H5Dget_create_plist(ds.id), H5Pclose};
  H5Handle type{H5Dget_type(ds.id), H5Tclose};
  const double declared = static_cast<double>(dims[0]) * cols * static_cast<double>(H5Tget_size(type.id));
  if (H5Pget_nfilters(dcpl.id) == 0 && static_cast<double>(H5Dget_storage_size(ds.id)) < declared)
    throw InputError(name + 1, "dataset declares " + std::to_string(dims[0]) +
                                   " rows but the file does not store them (truncated or corrupt?) in " + path);
  return dims[0];
}

/// Part `part` of `parts` of the rows of an HDF5 packing (rows [first, first
/// + count), read by hyperslab), with the file's attributes; total = N.
Packing read_h5_rows(const std::string& path, std::uint64_t part, std::uint64_t parts, std::uint64_t& first,
                     std::uint64_t& total) {
  std::lock_guard<std::recursive_mutex> lock(h5_mutex());
  h5_silence();
  if (H5Fis_hdf5(path.c_str()) <= 0) throw InputError("file", "'" + path + "' is not a readable HDF5 file");
  H5Handle f{H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  if (f.id < 0) throw InputError("file", "'" + path + "' could not be opened as HDF5 (truncated or corrupt?)");
  H5Handle root{H5Gopen2(f.id, "/", H5P_DEFAULT), H5Gclose};
  if (root.id < 0) throw InputError("file", "'" + path + "' has no readable root group (corrupt?)");
  Packing p;
  const auto dv = h5_read_double_attr(root.id, "d", path);
  if (dv.size() != 1 || !(dv[0] == 2 || dv[0] == 3))
    throw InputError("d", "attribute must be 2 or 3 in " + path);
  p.d = static_cast<int>(dv[0]);
  const auto box = h5_read_double_attr(root.id, "box", path);
  if (box.size() != static_cast<std::size_t>(p.d))
    throw InputError("box", "attribute must have d = " + std::to_string(p.d) + " values in " + path);
  for (int a = 0; a < p.d; ++a) p.box[a] = box[a];
  p.boundary = parse_boundary(h5_read_string_attr(root.id, "boundary", path));
  if (h5_has_attr(root.id, "tilt")) {  // a tilted box: xy (2D), xy xz yz (3D)
    const auto t = h5_read_double_attr(root.id, "tilt", path);
    if (t.size() != (p.d == 2 ? 1u : 3u))
      throw InputError("tilt", "attribute must have " + std::string(p.d == 2 ? "1 value (xy)" : "3 values (xy xz yz)") +
                                   " in " + path);
    for (std::size_t k = 0; k < t.size(); ++k) p.tilt[k] = t[k];
  }
  const hsize_t n = declared_rows(f.id, "/positions", p.d, path, parts);
  if (declared_rows(f.id, "/radii", 1, path, parts) != n)
    throw InputError("radii", "dataset must have N = " + std::to_string(n) + " values in " + path);
  total = n;
  first = n * part / parts;
  const hsize_t count = n * (part + 1) / parts - first;
  p.positions = h5_read_rows(f.id, "/positions", first, count, p.d, path);
  p.radii = h5_read_rows(f.id, "/radii", first, count, 1, path);
  for (const char* name : kStringAttrs)
    if (h5_has_attr(root.id, name)) p.str_attrs[name] = h5_read_string_attr(root.id, name, path);
  for (const char* name : kNumberAttrs)
    if (h5_has_attr(root.id, name)) {
      const auto v = h5_read_double_attr(root.id, name, path);
      if (v.size() == 1) p.num_attrs[name] = v[0];
    }
  return p;
}

Packing read_h5(const std::string& path) {
  std::uint64_t first = 0, total = 0;
  return read_h5_rows(path, 0, 1, first, total);
}

// ---- HDF5 in a child process ------------------------------------------------

/// The packing (or the error) as bytes through a pipe.
void put(std::string& out, const void* p, std::size_t n) { out.append(static_cast<const char*>(p), n); }
void put_str(std::string& out, const std::string& s) {
  const std::uint64_t n = s.size();
  put(out, &n, sizeof n);
  out += s;
}
struct Reader {
  const std::string& in;
  std::size_t at = 0;
  void get(void* p, std::size_t n) {
    if (at + n > in.size()) throw std::runtime_error("isolated HDF5 read: short message");
    std::memcpy(p, in.data() + at, n);
    at += n;
  }
  std::uint64_t u64() {
    std::uint64_t v;
    get(&v, sizeof v);
    return v;
  }
  std::string str() {
    const std::uint64_t n = u64();
    if (n > in.size() - at) throw std::runtime_error("isolated HDF5 read: short message");
    std::string s = in.substr(at, n);
    at += n;
    return s;
  }
};

std::string encode(const Packing& p) {
  std::string out = "P";
  const std::uint64_t d = p.d, b = p.boundary == Boundary::walls, n = p.size();
  put(out, &d, 8), put(out, &b, 8), put(out, p.box.data(), 3 * sizeof(double));
  put(out, p.tilt.data(), 3 * sizeof(double)), put(out, &n, 8);
  put(out, p.positions.data(), p.positions.size() * sizeof(double));
  put(out, p.radii.data(), p.radii.size() * sizeof(double));
  const std::uint64_t ns = p.str_attrs.size(), nn = p.num_attrs.size();
  put(out, &ns, 8);
  for (const auto& [k, v] : p.str_attrs) put_str(out, k), put_str(out, v);
  put(out, &nn, 8);
  for (const auto& [k, v] : p.num_attrs) put_str(out, k), put(out, &v, sizeof v);
  return out;
}

Packing decode(const std::string& in) {
  Reader r{in, 1};
  Packing p;
  p.d = static_cast<int>(r.u64());
  p.boundary = r.u64() ? Boundary::walls : Boundary::periodic;
  r.get(p.box.data(), 3 * sizeof(double));
  r.get(p.tilt.data(), 3 * sizeof(double));
  const std::uint64_t n = r.u64();
  if (n > kMaxParticles || (p.d != 2 && p.d != 3)) throw std::runtime_error("isolated HDF5 read: bad message");
  p.positions.resize(n * p.d);
  p.radii.resize(n);
  r.get(p.positions.data(), p.positions.size() * sizeof(double));
  r.get(p.radii.data(), p.radii.size() * sizeof(double));
  for (std::uint64_t i = 0, ns = r.u64(); i < ns; ++i) {
    std::string k = r.str();
    p.str_attrs[k] = r.str();
  }
  for (std::uint64_t i = 0, nn = r.u64(); i < nn; ++i) {
    std::string k = r.str();
    double v;
    r.get(&v, sizeof v);
    p.num_attrs[k] = v;
  }
  return p;
}

Packing read_h5_in_child(const std::string& path, double base_seconds) {
  int fd[2];
  if (::pipe(fd) != 0) throw std::runtime_error("pipe failed");
  std::error_code ec;
  const double bytes = static_cast<double>(std::filesystem::file_size(path, ec));
  const double limit = base_seconds + (ec ? 0.0 : bytes / 1e8);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {  // the child: read, send, and leave without running atexit handlers
    ::close(fd[0]);
    // The default actions, not the caller's handlers (a fuzzer or a sanitizer
    // has some): a crash or the alarm ends the child, and the parent sees it.
    for (int sig : {SIGALRM, SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) std::signal(sig, SIG_DFL);
    itimerval timer{};
    timer.it_value.tv_sec = static_cast<time_t>(limit);
    timer.it_value.tv_usec = static_cast<suseconds_t>((limit - std::floor(limit)) * 1e6);
    ::setitimer(ITIMER_REAL, &timer, nullptr);
    std::string msg;
    try {
      msg = encode(read_h5(path));
    } catch (const InputError& e) {
      msg = "E";
      put_str(msg, e.field());
      put_str(msg, e.what());
    } catch (const std::exception& e) {
      msg = "X";
      put_str(msg, e.what());
    }
    for (std::size_t at = 0; at < msg.size();) {
      const ssize_t w = ::write(fd[1], msg.data() + at, msg.size() - at);
      if (w <= 0) ::_exit(3);
      at += static_cast<std::size_t>(w);
    }
    ::_exit(0);
  }
  ::close(fd[1]);
  std::string msg;
  char buf[1 << 16];
  for (ssize_t r; (r = ::read(fd[0], buf, sizeof buf)) != 0;) {
    if (r < 0) {
      if (errno == EINTR) continue;
      break;
    }
    msg.append(buf, static_cast<std::size_t>(r));
  }
  ::close(fd[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status))
    throw InputError("file", "'" + path + "' is corrupt: the HDF5 library " +
                                 (WTERMSIG(status) == SIGALRM ? "did not finish reading it in " + format_number(limit) + " s"
                                                              : "crashed reading it (signal " +
                                                                    std::to_string(WTERMSIG(status)) + ")"));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || msg.empty())
    throw InputError("file", "'" + path + "' is corrupt: the HDF5 library failed reading it (exit status " +
                                 std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  if (msg[0] == 'E') {
    Reader r{msg, 1};
    const std::string field = r.str(), what = r.str();
    throw InputError(field, what.substr(std::min(what.size(), field.size() + 2)));
  }
  if (msg[0] == 'X') {
    Reader r{msg, 1};
    throw std::runtime_error(r.str());
  }
  return decode(msg);
}

}  // namespace

Packing parse_packing_csv(std::istream& in, const std::string& name) {
  std::ostringstream text;
  text << in.rdbuf();
  return to_packing(parse_particles(text.str(), name), name);
}

Packing read_hdf5_packing(const std::string& path, Isolation isolation, double base_seconds) {
  return isolation == Isolation::child_process ? read_h5_in_child(path, base_seconds) : read_h5(path);
}

Packing read_packing_part(const std::string& path, std::uint64_t part, std::uint64_t parts, std::uint64_t& first,
                          std::uint64_t& total) {
  if (parts < 1 || part >= parts) throw InputError("part", "must be below the number of parts");
  if (!hdf5_file(path)) {
    Packing all = read_packing(path, Isolation::none);
    total = all.size();
    first = total * part / parts;
    const std::uint64_t end = total * (part + 1) / parts;
    all.radii = std::vector<double>(all.radii.begin() + first, all.radii.begin() + end);
    all.positions = std::vector<double>(all.positions.begin() + first * all.d, all.positions.begin() + end * all.d);
    return all;
  }
  if (!std::filesystem::exists(path)) throw InputError("file", "'" + path + "' does not exist");
  Packing p = read_h5_rows(path, part, parts, first, total);
  validate(p, first);
  return p;
}

Packing read_packing(const std::string& path, Isolation isolation, double base_seconds,
                     std::optional<std::int64_t> frame) {
  if (!hdf5_file(path)) return to_packing(read_particles(path, isolation, frame), path);
  detail::resolve_frame(frame, 1, path);  // an HDF5 packing is one snapshot
  if (!std::filesystem::exists(path)) throw InputError("file", "'" + path + "' does not exist");
  Packing p = read_hdf5_packing(path, isolation, base_seconds);  // with the file's attributes
  validate(p);
  return p;
}

void write_packing(const std::string& path, const Packing& p) {
  detail::h5_write_file(path, [&](hid_t f) {
    const hsize_t n = p.size();
    detail::h5_write_dataset(f, "/positions", p.positions, {n, static_cast<hsize_t>(p.d)});
    detail::h5_write_dataset(f, "/radii", p.radii, {n});
    detail::H5Handle root{H5Gopen2(f, "/", H5P_DEFAULT), H5Gclose};
    detail::h5_write_attr(root.id, "d", std::int64_t{p.d});
    detail::h5_write_attr(root.id, "box", std::vector<double>(p.box.begin(), p.box.begin() + p.d));
    detail::h5_write_attr(root.id, "boundary", std::string(to_string(p.boundary)));
    if (p.tilted())
      detail::h5_write_attr(root.id, "tilt", tilt_values(p.tilt, p.d));
    for (const auto& [k, v] : p.num_attrs) detail::h5_write_attr(root.id, k, std::vector<double>{v});
    for (const auto& [k, v] : p.str_attrs) detail::h5_write_attr(root.id, k, v);
    for (const auto& [k, v] : provenance_fields())
      if (!p.str_attrs.count(k)) detail::h5_write_attr(root.id, k, v);
  });
}

}  // namespace hgrid
