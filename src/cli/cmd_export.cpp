// hgrid export: a packing (a file, or generation options with the packing
// cache) as a LAMMPS data file and the two timing scripts (--lammps DIR), and
// as files for viewers with each particle's level and cell (--xyz, --vtk).
#include <cmath>
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>

#include "common.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/packing/generate.hpp"
#include "hgridlab/io/lammps_export.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/io/peer_settings.hpp"
#include "hgridlab/io/viewer_files.hpp"
#include "hgridlab/calibration/k_choice.hpp"
#include "hgridlab/io/packing_cache.hpp"
#include "hgridlab/advice/recommend.hpp"
#include "hgridlab/packing/grid_placement.hpp"

namespace hgrid::cli {
namespace {

struct ExportOptions {
  std::string file, lammps, cache_dir = "results/packings", boundary = "periodic", placement = "excluded";
  std::optional<std::int64_t> frame;
  std::string collections, xyz, vtk, sizes, K;
  int classes = 4;
  double smallest = 0;  // 0: 2 r_min
  PackingSpec spec;
  int builds = 10;
};


void run_export(ExportOptions o) {
  if (o.lammps.empty() && o.xyz.empty() && o.vtk.empty())
    throw InputError("out", "give --lammps DIR, --xyz FILE or --vtk FILE");
  Packing p;
  if (!o.file.empty()) {
    if (o.spec.n != 0) throw InputError("n", "give either FILE or generation options (--n ...), not both");
    p = read_packing(o.file, Isolation::child_process, kIsolatedReadBaseSeconds, o.frame);
  } else {
    if (o.spec.n == 0) throw InputError("n", "give FILE or --n N (and the other generation options)");
    o.spec.boundary = parse_boundary(o.boundary);
    o.spec.placement = parse_placement(o.placement);
    p = cached_packing(o.spec, o.cache_dir);
  }
  // Everything is computed and checked before the first file is written.
  LammpsScript s;
  s.builds = o.builds;
  // What `hgrid recommend` gives the packing (its density field when it
  // has positions), computed once for the sizes and the collections.
  std::optional<Recommendation> advice;
  const auto recommended = [&]() -> const Recommendation& {
    if (!advice) advice = recommend_for_packing(p, choose_K(o.K).K);
    return *advice;
  };
  if (o.collections == "model") {  // as `hgrid recommend` gives them: LAMMPS's own cost model
    s.collections = rounded_up_sizes(recommended().lammps_collections);
  } else if (!o.collections.empty()) {
    s.collections = parse_list(o.collections, "collections");
  } else {
    double rmin = p.radii.empty() ? 1.0 : p.radii[0];
    for (double r : p.radii) rmin = std::min(rmin, r);
    if (!(std::isfinite(o.smallest) && o.smallest >= 0))
      throw InputError("smallest", "must be a finite number > 0, or 0 for 2 r_min (got " + format_number(o.smallest) + ")");
    s.collections = geometric_collections(p, o.classes, o.smallest > 0 ? o.smallest : 2 * rmin);
  }
  if (!o.lammps.empty()) lammps_input(p, s);  // validates the classes
  GridPlacement g;
  if (!o.xyz.empty() || !o.vtk.empty()) {
    const std::vector<double> sizes = o.sizes.empty() ? recommended().sizes : parse_list(o.sizes, "sizes");
    g = place_in_grid(p, GridParams{sizes, Search::top_down});
  }
  // The files written, one per line on stdout; not a stream written in
  // place (`--xyz /dev/stdout` is the data alone).
  const auto written = [](const std::string& f) {
    if (std::filesystem::is_regular_file(f)) std::cout << f << "\n";
  };
  if (!o.xyz.empty()) write_extended_xyz(o.xyz, p, g), written(o.xyz);
  if (!o.vtk.empty()) write_legacy_vtk(o.vtk, p, g), written(o.vtk);
  if (!o.lammps.empty()) {
    export_lammps(o.lammps, p, s);
    std::cout << o.lammps << "/data.lmp\n" << o.lammps << "/in.multi.lmp\n" << o.lammps << "/in.bin.lmp\n";
  }
}

}  // namespace

void register_export_commands(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  auto* sub = app.add_subcommand("export", "export a packing for another code (LAMMPS) or a viewer (OVITO, ParaView)");
  sub->add_option("FILE", o->file, "packing file (any format with centres and a box); or give generation options");
  add_frame_option(sub, o->frame);
  sub->add_option("--lammps", o->lammps, "output directory: data.lmp, in.multi.lmp, in.bin.lmp");
  sub->add_option("--xyz", o->xyz, "extended XYZ file (OVITO): radius, level of insertion, cell per particle");
  sub->add_option("--vtk", o->vtk, "legacy VTK file (ParaView): radius, level of insertion, cell per particle");
  sub->add_option("--sizes", o->sizes, "--xyz/--vtk: cell sizes s1,...,sL (default: those of `hgrid recommend`)");
  sub->add_option("--K", o->K, std::string(kKHelp) + " (for recommended sizes; default as `hgrid recommend`)");
  sub->add_option("--collections", o->collections,
                  "multi: size-class upper bounds as diameters c1,...,ck (last >= largest diameter), or 'model': "
                  "the LAMMPS collections of `hgrid recommend` (LAMMPS's own cost model)");
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
