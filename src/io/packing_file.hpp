// Packing files: read any supported format, write HDF5 with provenance.
#pragma once
#include <cstdint>
#include <istream>
#include <optional>
#include <string>

#include "hgridlab/packing/packing.hpp"

namespace hgrid {

/// How an HDF5 file is read. libhdf5 can crash or loop forever on a corrupt
/// file (a flipped byte in its global heap, say); `child_process` reads it in
/// a forked child with a time limit, so that such a file is refused with an
/// InputError instead. For files from outside (the command-line tool); fork
/// from a single-threaded caller only.
enum class Isolation { none, child_process };

/// Seconds a child may take to read an HDF5 file: this plus one per 100 MB
/// (`base_seconds` below; the fuzz target gives a shorter one, so that a
/// file libhdf5 loops on costs it a fraction of a second, not five).
inline constexpr double kIsolatedReadBaseSeconds = 5;

/// Reads a packing from any particle file that has centres and a box (HDF5,
/// CSV or text with `# box`, LAMMPS data and dump files; io/particle_file.hpp),
/// validates it (see validate()) and returns it. Throws InputError naming the
/// field that is wrong.
/// `frame`: the snapshot of a file that holds several (read_particles).
Packing read_packing(const std::string& path, Isolation isolation = Isolation::none,
                     double base_seconds = kIsolatedReadBaseSeconds, std::optional<std::int64_t> frame = std::nullopt);

/// Part `part` of `parts` (0-based) of a packing file: its rows [first,
/// first + count) with first = N part / parts, validated like read_packing
/// (messages name the file's particle index); total receives N. An HDF5
/// file is read by hyperslab: only those rows are read, so that each of P
/// processes holds its own part of a file too large for one of them. The
/// text formats are read whole, then cut. Not isolated (Isolation::none).
Packing read_packing_part(const std::string& path, std::uint64_t part, std::uint64_t parts, std::uint64_t& first,
                          std::uint64_t& total);

/// Reads a packing from text in any of the text formats; `name` names the
/// source in messages.
Packing parse_packing_csv(std::istream& in, const std::string& name);

/// An HDF5 packing file as stored (not validated).
Packing read_hdf5_packing(const std::string& path, Isolation isolation,
                          double base_seconds = kIsolatedReadBaseSeconds);

/// Writes a packing as HDF5 (datasets /positions N x d and /radii N; root
/// attributes d, box, boundary, the packing's own attributes and the
/// provenance record), atomically: a temporary file renamed into place.
void write_packing(const std::string& path, const Packing& p);

}  // namespace hgrid
