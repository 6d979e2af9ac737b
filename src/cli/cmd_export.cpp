// hgrid export --lammps DIR: a packing (a file, or generation options with the
// packing cache) as a LAMMPS data file and the two timing scripts.
#include <cmath>
#include <algorithm>
#include <iostream>
#include <memory>

#include "cli/common.hpp"
#include "grid/error.hpp"
#include "packing/generate.hpp"
#include "io/lammps_export.hpp"
#include "io/packing_file.hpp"
#include "experiment/packing_cache.hpp"

namespace hgrid::cli {
namespace {

struct ExportOptions {
  std::string file, lammps, cache_dir = "results/packings", boundary = "periodic", placement = "excluded";
  std::string collections;
  int classes = 4;
  double smallest = 0;  // 0: 2 r_min
  PackingSpec spec;
  int builds = 10;
};

void run_export(ExportOptions o) {
  if (o.lammps.empty()) throw InputError("lammps", "give --lammps DIR");
  Packing p;
  if (!o.file.empty()) {
    if (o.spec.n != 0) throw InputError("n", "give either FILE or generation options (--n ...), not both");
    p = read_packing(o.file, Isolation::child_process);
  } else {
    if (o.spec.n == 0) throw InputError("n", "give FILE or --n N (and the other generation options)");
    o.spec.boundary = parse_boundary(o.boundary);
    o.spec.placement = parse_placement(o.placement);
    p = cached_packing(o.spec, o.cache_dir);
  }
  LammpsScript s;
  s.builds = o.builds;
  if (!o.collections.empty()) {
    s.collections = parse_list(o.collections, "collections");
  } else {
    double rmin = p.radii.empty() ? 1.0 : p.radii[0];
    for (double r : p.radii) rmin = std::min(rmin, r);
    if (!(std::isfinite(o.smallest) && o.smallest >= 0))
      throw InputError("smallest", "must be a finite number > 0, or 0 for 2 r_min (got " + format_number(o.smallest) + ")");
    s.collections = geometric_collections(p, o.classes, o.smallest > 0 ? o.smallest : 2 * rmin);
  }
  export_lammps(o.lammps, p, s);
  std::cout << o.lammps << "/data.lmp\n" << o.lammps << "/in.multi.lmp\n" << o.lammps << "/in.bin.lmp\n";
}

}  // namespace

void register_export_commands(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  auto* sub = app.add_subcommand("export", "export a packing for another code (LAMMPS data file and scripts)");
  sub->add_option("FILE", o->file, "packing file (.h5 or .csv); or give generation options");
  sub->add_option("--lammps", o->lammps, "output directory: data.lmp, in.multi.lmp, in.bin.lmp")->required();
  sub->add_option("--collections", o->collections,
                  "multi: size-class upper bounds as diameters c1,...,ck (last >= largest diameter)");
  sub->add_option("--classes", o->classes, "multi, without --collections: k geometric classes")->default_val(4);
  sub->add_option("--smallest", o->smallest, "multi, without --collections: smallest class bound (default 2 r_min)");
  sub->add_option("--builds", o->builds, "timed neighbour-list builds per run")->default_val(10);
  sub->add_option("--d", o->spec.d, "generate: dimension, 2 or 3")->default_val(3);
  sub->add_option("--n", o->spec.n, "generate: number of particles")->check(CLI::NonNegativeNumber);
  sub->add_option("--nu", o->spec.nu, "generate: packing fraction")->default_val(0.6);
  sub->add_option("--alpha", o->spec.alpha, "generate: power-law exponent")->default_val(-3.0);
  sub->add_option("--omega", o->spec.omega, "generate: r_max / r_min")->default_val(100.0);
  sub->add_option("--boundary", o->boundary, "generate: periodic|walls")->default_val("periodic");
  sub->add_option("--placement", o->placement, "generate: random|excluded")->default_val("excluded");
  sub->add_option("--seed", o->spec.seed, "generate: random seed")->default_val(1)->check(CLI::NonNegativeNumber);
  sub->add_option("--cache", o->cache_dir, "generate: packing cache directory")->default_val("results/packings");
  sub->callback([o] { run_export(*o); });
}

}  // namespace hgrid::cli
