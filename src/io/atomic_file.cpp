#include "hgridlab/io/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "hgridlab/base/error.hpp"

namespace hgrid {

namespace fs = std::filesystem;

void write_file_atomically(const std::string& path, const std::function<void(const std::string& tmp)>& write,
                           const std::string& field) {
  std::error_code ec;
  const fs::file_status target = fs::status(path, ec);  // through symlinks: /dev/stdout is one
  if (!ec && fs::exists(target) && !fs::is_regular_file(target) && !fs::is_directory(target)) {
    // A pipe, a device or a socket (/dev/stdout, /dev/null, a FIFO): written
    // in place. A rename would replace it by a regular file (as root, the
    // machine's /dev/stdout), and a stream has no partial file to avoid.
    write(path);
    return;
  }
  static std::atomic<unsigned> counter{0};
  const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw InputError(field, "cannot write '" + path + "': " + ec.message());
  }
}

void write_stream_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                             const std::string& field) {
  write_file_atomically(
      path,
      [&](const std::string& tmp) {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw InputError(field, "cannot create '" + tmp + "'");
        write(out);
        out.close();
        if (!out) throw InputError(field, "write failed for '" + path + "' (disk full?)");
      },
      field);
}

void write_text_atomically(const std::string& path, std::string_view text, const std::string& field) {
  write_stream_atomically(path, [&](std::ostream& out) { out << text; }, field);
}

int remove_stale_temporaries(const std::string& dir, std::chrono::seconds max_age) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  const auto now = fs::file_time_type::clock::now();
  int removed = 0;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp.") == std::string::npos || !e.is_regular_file(ec)) continue;
    const auto t = e.last_write_time(ec);
    if (ec || now - t < max_age) continue;
    if (fs::remove(e.path(), ec)) ++removed;
  }
  return removed;
}

}  // namespace hgrid
