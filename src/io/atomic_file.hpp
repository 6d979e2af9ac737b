// Writing a file so that it exists whole or not at all: the one helper every
// output goes through (a temporary name beside the target, then a rename).
#pragma once
#include <chrono>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>

namespace hgrid {

/// Calls write(tmp) with a temporary file name beside `path` (unique per
/// process and call: "<path>.tmp.<pid>.<n>"), then renames it to `path`.
/// Whatever fails (write throws, the rename fails: `path` is a directory, the
/// disk is full), the temporary file is removed and nothing is left behind;
/// a failed rename throws InputError naming `field`. A `path` that is a
/// pipe, a device or a socket (/dev/stdout, a FIFO) is written in place.
void write_file_atomically(const std::string& path, const std::function<void(const std::string& tmp)>& write,
                           const std::string& field = "out");

/// Same, with a stream: write(out) fills the file; a stream error (a full
/// disk, say) throws InputError naming `field`.
void write_stream_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                             const std::string& field = "out");

/// Same, with the whole text at once.
void write_text_atomically(const std::string& path, std::string_view text, const std::string& field = "out");

/// Age after which a temporary file is a leftover: no write of this project
/// takes this long between creating its temporary file and renaming it.
inline constexpr std::chrono::seconds kStaleTemporaryAge{600};

/// Removes temporary files ("*.tmp.*") in dir that are older than max_age:
/// the leftovers of runs killed before they could remove them. Returns how
/// many were removed; a missing dir is not an error.
int remove_stale_temporaries(const std::string& dir, std::chrono::seconds max_age);

}  // namespace hgrid
