// Helpers shared by the hgrid subcommands.
#pragma once
#include <CLI/CLI.hpp>

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>

#include "hgridlab/grid/params.hpp"
#include "hgridlab/base/threads.hpp"
#include "hgridlab/io/particle_file.hpp"

namespace hgrid::cli {

/// Buffered "i j\n" writer to stdout for large pair lists (pairs, serial
/// and decomposed).
class PairWriter {
 public:
  void operator()(std::uint64_t i, std::uint64_t j) {
    if (buf_.size() - used_ < 48) flush();  // two 20-digit numbers and 2 bytes
    char* p = buf_.data() + used_;
    p = std::to_chars(p, buf_.data() + buf_.size(), i).ptr;
    *p++ = ' ';
    p = std::to_chars(p, buf_.data() + buf_.size(), j).ptr;
    *p++ = '\n';
    used_ = static_cast<std::size_t>(p - buf_.data());
  }
  void flush() {
    std::fwrite(buf_.data(), 1, used_, stdout);
    used_ = 0;
  }
  ~PairWriter() { flush(); }

 private:
  std::string buf_ = std::string(1 << 16, '\0');
  std::size_t used_ = 0;
};

/// Each subcommand file provides one of these; main.cpp calls them all.
void register_pairs_commands(CLI::App& app);  // pairs            (cmd_pairs.cpp)
void register_count_commands(CLI::App& app);  // count            (cmd_count.cpp)
void register_model_commands(CLI::App& app);  // model             (cmd_model.cpp)
void register_modelfigs_commands(CLI::App& app);  // modelfigs     (cmd_modelfigs.cpp)
void register_fields_commands(CLI::App& app);  // fields           (cmd_fields.cpp)
void register_generate_commands(CLI::App& app);  // generate, info (cmd_generate.cpp)
void register_run_commands(CLI::App& app);       // run           (cmd_run.cpp)
void register_export_commands(CLI::App& app);    // export        (cmd_export.cpp)
void register_calibrate_commands(CLI::App& app);  // calibrate   (cmd_calibrate.cpp)
void register_recommend_commands(CLI::App& app);  // recommend   (cmd_recommend.cpp)

/// A --K option's text: a number >= 0, or "auto" (the stored calibration).
inline constexpr const char* kKHelp =
    "cell access time / overlap test time (>= 0), or 'auto': the K measured by `hgrid calibrate`";

/// Exit status for bad input (file, parameter): one line on stderr, status 2.
inline constexpr int kBadInput = 2;


/// The --threads option of a command that searches (default 0: all cores,
/// OMP_NUM_THREADS when set); checked by hgrid::check_threads (base/threads.hpp).
void add_threads_option(CLI::App* sub, int& threads);
/// The --frame option of a command that reads a particle file: the snapshot
/// of a file that holds several (LAMMPS dump, MercuryDPM .data), from the
/// first (0-based) or from the end when negative; default: the last.
void add_frame_option(CLI::App* sub, std::optional<std::int64_t>& frame);

/// The --decompose forms of pairs and count (cmd_decompose.cpp): the search
/// split over the ranks of an MPI run; rank 0 prints.
void run_decomposed_pairs(const std::string& file, const GridParams& g);
void run_decomposed_count(const std::string& file, const GridParams& g, double K, bool as_json);
/// A --threads value under MPI: 0 (all cores) shares the cores among the
/// ranks on this machine unless OMP_NUM_THREADS says otherwise.
int threads_per_rank(int threads);

/// Parse "a,b,c" into doubles; throws hgrid::InputError naming `field`.
std::vector<double> parse_list(const std::string& text, const std::string& field);

}  // namespace hgrid::cli
