// hgrid: the command-line front end of hgridlab.
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstdio>
#include <exception>
#include <iostream>
#include <sstream>
#include <string>

#include "common.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/base/heap.hpp"
#include "hgridlab/io/provenance.hpp"
#include "hgridlab/mpi/comm.hpp"

namespace hgrid::cli {

void add_threads_option(CLI::App* sub, int& threads) {
  sub->add_option("--threads", threads,
                  "threads of the build and the search: 0 = all cores (OMP_NUM_THREADS when set), or 1 to " +
                      std::to_string(kMaxThreads) + "; the results are the same for any number")
      ->default_val(0);
}

void add_frame_option(CLI::App* sub, std::optional<std::int64_t>& frame) {
  sub->add_option("--frame", frame,
                  "snapshot of a file that holds several (LAMMPS dump, MercuryDPM .data): K from the first "
                  "(0, 1, ...) or from the end (-1, -2, ...); default: the last");
}

std::vector<double> parse_list(const std::string& text, const std::string& field) {
  std::vector<double> out;
  if (text.empty()) throw InputError(field, "empty list");
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    // strtod, not stod: a denormal is a number (stod calls it out of range).
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size())
      throw InputError(field, "'" + item + "' is not a number (expected a comma-separated list)");
    if (!std::isfinite(v)) throw InputError(field, "'" + item + "' is not a finite number");
    out.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace hgrid::cli

namespace {

int parse_and_run(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // An unknown option is named as such, even when a required one is also
    // missing (CLI11 reports the missing one first).
    const auto extra = app.remaining(true);
    if (!extra.empty()) std::cerr << "hgrid: error: " << extra.front() << ": unknown option or argument (see --help)\n";
    else std::cerr << "hgrid: " << e.what() << " (see --help)\n";
    return hgrid::cli::kBadInput;
  } catch (const hgrid::mpi::PeerFailed& e) {
    return e.status;  // rank 0 reports it
  } catch (const hgrid::InputError& e) {
    // Under MPI every rank meets the same bad input; rank 0 says so.
    if (hgrid::mpi::rank() == 0) std::cerr << "hgrid: error: " << e.what() << "\n";
    return hgrid::cli::kBadInput;
  } catch (const std::exception& e) {
    // Not agreed on: every rank that meets one says so.
    if (hgrid::mpi::size() > 1) std::cerr << "hgrid (rank " << hgrid::mpi::rank() << "): ";
    else std::cerr << "hgrid: ";
    std::cerr << "internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  hgrid::keep_freed_memory();  // before any thread: the grids built and dropped in loops reuse their pages
  // MPI only when mpirun or srun started this process (mpi/comm.hpp).
  const hgrid::mpi::Session mpi_session(argc, argv);
  if (!hgrid::mpi::built_with_mpi() && hgrid::mpi::launched_ranks() > 1) {
    // P copies of a plain run would each do all the work into the same files.
    const char* r = std::getenv("OMPI_COMM_WORLD_RANK");
    if (!r || std::string(r) == "0")
      std::cerr << "hgrid: error: mpi: this hgrid was built without MPI (install libopenmpi-dev and rebuild); "
                   "run it without mpirun/srun\n";
    return hgrid::cli::kBadInput;
  }
  CLI::App app{"hgrid: hierarchical-grid contact detection, counted, and its cost model\n"
               "(Krijgsman, Ogarko & Luding, Comp. Part. Mech. 1 (2014) 357-372)"};
  app.set_version_flag("--version", std::string("hgrid ") + hgrid::version() + " (" + hgrid::git_hash() + ", " +
                                        hgrid::compiler_id() + ")");
  app.require_subcommand(1);
  app.fallthrough(false);
  hgrid::cli::register_pairs_commands(app);
  hgrid::cli::register_count_commands(app);
  hgrid::cli::register_model_commands(app);
  hgrid::cli::register_modelfigs_commands(app);
  hgrid::cli::register_fields_commands(app);
  hgrid::cli::register_generate_commands(app);
  hgrid::cli::register_run_commands(app);
  hgrid::cli::register_export_commands(app);
  hgrid::cli::register_calibrate_commands(app);
  hgrid::cli::register_recommend_commands(app);
  // An empty value ("--cells ''") is refused, not taken for "not given".
  const CLI::Validator non_empty([](std::string& v) { return v.empty() ? std::string("must not be empty") : ""; },
                                 "", "non-empty");
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    for (CLI::Option* opt : sub->get_options())
      if (opt->get_type_size() > 0 && opt->get_expected_min() > 0) opt->check(non_empty);
  // A closed pipe is an output error reported like any other (below), not a
  // death by signal.
  std::signal(SIGPIPE, SIG_IGN);
  const int rc = parse_and_run(app, argc, argv);
  // Output that did not reach its destination (a full disk, a closed pipe)
  // is an error, not a success.
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::cerr << "hgrid: error: stdout: the output could not be written (disk full or pipe closed)\n";
    return 1;
  }
  return rc;
}
