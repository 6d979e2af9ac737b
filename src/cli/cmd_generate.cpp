// hgrid generate: packings for the experiments (random or excluded-volume
// placement), written as HDF5; also registers `hgrid info` (cmd_info.cpp).
#include <filesystem>
#include <iostream>
#include <memory>

#include "common.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/base/threads.hpp"
#include "hgridlab/packing/generate.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/io/packing_cache.hpp"

namespace hgrid::cli {

void register_info_command(CLI::App& app);  // cmd_info.cpp

namespace {

struct GenerateOptions {
  PackingSpec spec;
  std::string boundary = "periodic", placement = "random", method = "auto", stop = "sweeps", moves = "metropolis", out, cache_dir,
      from;
  bool quiet = false;
  bool sweeps_given = false, tol_given = false;
};

void run_generate(GenerateOptions o) {
  o.spec.boundary = parse_boundary(o.boundary);
  o.spec.placement = parse_placement(o.placement);
  o.spec.method = parse_excluded_method(o.method);
  o.spec.stop = parse_equilibration_stop(o.stop);
  o.spec.moves = parse_equilibration_moves(o.moves);
  o.spec.progress = !o.quiet;
  if (o.out.empty() == o.cache_dir.empty()) throw InputError("out", "give exactly one of --out FILE and --cache DIR");
  if (o.spec.equilibrate && o.spec.placement != Placement::excluded)
    throw InputError("equilibrate", "only applies to --placement excluded");
  if (o.sweeps_given && !o.spec.equilibrate) throw InputError("sweeps", "only applies with --equilibrate");
  if (o.tol_given && o.spec.stop != EquilibrationStop::stationary)
    throw InputError("stationary_tol", "only applies with --stop stationary");
  if (!o.from.empty() && (!o.spec.equilibrate || o.out.empty()))
    throw InputError("from", "only applies with --equilibrate and --out (--cache resumes by itself)");
  Packing p;
  std::string path = o.out;
  bool reused = false;  // --cache and the packing was there already
  if (!o.cache_dir.empty()) {
    path = packing_cache_path(o.spec, o.cache_dir);
    reused = std::filesystem::exists(path);
    p = cached_packing(o.spec, o.cache_dir);
  } else if (!o.from.empty()) {
    const Packing start = read_packing(o.from);
    const std::string why = resume_mismatch(start, o.spec);
    if (!why.empty()) throw InputError("from", "cannot continue " + o.from + ": " + why);
    p = generate_packing(o.spec, &start);
    write_packing(o.out, p);
  } else {
    p = generate_packing(o.spec);
    write_packing(o.out, p);
  }
  std::cerr << "hgrid generate: " << (reused ? "reused " : "wrote ") << path << " (n = " << p.size() << ", nu = " << p.num_attrs["nu_achieved"]
            << ", max rel. overlap (-1: not computed) = "
            << (p.num_attrs.count("max_rel_overlap") ? p.num_attrs["max_rel_overlap"] : -1.0) << ", seed = " << o.spec.seed << ")\n";
  if (!o.cache_dir.empty()) std::cout << path << "\n";
}

}  // namespace

void register_generate_commands(CLI::App& app) {
  auto o = std::make_shared<GenerateOptions>();
  auto* sub = app.add_subcommand("generate", "generate a packing and write it as HDF5");
  sub->add_option("--d", o->spec.d, "dimension, 2 or 3")->default_val(3);
  sub->add_option("--n", o->spec.n, "number of particles")->required()->check(CLI::NonNegativeNumber);
  sub->add_option("--nu", o->spec.nu, "packing fraction (total particle volume / box volume), in (0, 1)")->required();
  sub->add_option("--dist", o->spec.dist, "radius distribution: powerlaw|lognormal")->default_val("powerlaw");
  sub->add_option("--alpha", o->spec.alpha, "power-law exponent of the radius pdf")->default_val(-3.0);
  sub->add_option("--omega", o->spec.omega, "size ratio r_max / r_min (r_min = 1), >= 1")->default_val(100.0);
  sub->add_option("--sigma", o->spec.sigma, "lognormal: sigma of ln r (median at sqrt(omega))")->default_val(0.5);
  sub->add_option("--boundary", o->boundary, "periodic|walls")->default_val("periodic");
  sub->add_option("--placement", o->placement, "random (independent centres) | excluded (no overlaps) | bed (no overlaps, settled under gravity onto the floor of the last axis; --boundary walls, --nu <= 0.3)")
      ->default_val("random");
  sub->add_option("--method", o->method,
                  "excluded: auto (sequential addition, growth + FIRE where it stalls) | rsa (sequential addition "
                  "only) | growth (sequential addition at nu = 0.35, then growth + FIRE)")
      ->default_val("auto");
  sub->add_flag("--equilibrate", o->spec.equilibrate,
                "excluded: hard-sphere Monte Carlo after placement (displacements and swaps of two particles)");
  auto* sweeps = sub->add_option("--sweeps", o->spec.sweeps,
                                 "with --equilibrate: Monte Carlo sweeps (N trials each), 1 to " +
                                     std::to_string(kMaxEquilibrationSweeps))
                     ->default_val(kDefaultEquilibrationSweeps);
  sub->add_option("--stop", o->stop,
                  "with --equilibrate: sweeps (run all --sweeps) | stationary (stop as soon as the packing's T/N under "
                  "its optimal Top-Down sizes, K = 0.2, is stationary within its noise; --sweeps is the cap)")
      ->default_val("sweeps");
  auto* tol = sub->add_option("--stationary-tol", o->spec.stationary_tol,
                  "with --stop stationary: the largest drift of T/N per doubling of the run, widened by two "
                  "standard errors, relative to T/N, in (0, 0.1]")
      ->default_val(kStationaryRelTol);
  sub->add_option("--moves", o->moves,
                  "with --equilibrate: metropolis (displacements and swaps, on all cores) | event-chain (event "
                  "chains along +x, +y, +z and the same swaps; one thread, periodic boxes)")
      ->default_val("metropolis");
  sub->add_option("--threads", o->spec.threads,
                  "excluded-volume placement: threads of sequential addition, growth + FIRE and --equilibrate's Monte Carlo, 0 = all cores (OMP_NUM_THREADS when set), or 1 to " +
                      std::to_string(kMaxThreads) + "; the packing is the same for any number")
      ->default_val(0);
  sub->add_option("--seed", o->spec.seed, "random seed")->default_val(1)->check(CLI::NonNegativeNumber);
  sub->add_option("--out", o->out, "output file (.h5)");
  sub->add_option("--cache", o->cache_dir,
                  "instead of --out: reuse or create DIR/<hash>.h5 (path printed); an equilibration resumes from the "
                  "furthest stage of it cached there (a killed run, or fewer sweeps asked before), else starts from "
                  "the packing's cached placement, and checkpoints every 5 min");
  sub->add_option("--from", o->from,
                  "with --equilibrate and --out: continue the equilibration recorded in FILE (the same parameters "
                  "at fewer sweeps, or without --equilibrate: its placement) to --sweeps; the result equals the "
                  "uninterrupted run's");
  sub->add_flag("--quiet", o->quiet, "no progress lines");
  sub->callback([o, sweeps, tol] {
    o->sweeps_given = sweeps->count() > 0;
    o->tol_given = tol->count() > 0;
    run_generate(*o);
  });
  register_info_command(app);
}

}  // namespace hgrid::cli
