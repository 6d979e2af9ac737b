// hgrid info: quality figures of a packing file, or a distribution's random
// close packing estimate (--rcp).
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "common.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/packing/generate.hpp"
#include "hgridlab/packing/rcp.hpp"
#include "hgridlab/io/packing_file.hpp"
#include "hgridlab/io/packing_report.hpp"
#include "hgridlab/io/particle_file.hpp"

namespace hgrid::cli {
namespace {

struct InfoOptions {
  std::string file;
  bool json = false, rcp = false;
  bool d_given = false;  // --d on the command line
  std::optional<std::int64_t> frame;
  PackingSpec spec;
};

void run_info(const InfoOptions& o) {
  if (o.rcp) {
    if (o.spec.d != 2 && o.spec.d != 3) throw InputError("d", "must be 2 or 3");
    const auto dist = make_distribution(o.spec);
    const double est = estimate_rcp(o.spec.d, *dist);
    if (o.json) std::cout << nlohmann::json{{"d", o.spec.d}, {"dist", o.spec.dist}, {"rcp_estimate", est}}.dump(2) << "\n";
    else std::cout << "random close packing estimate (de Larrard linear packing model): " << est << "\n";
    return;
  }
  if (o.file.empty()) throw InputError("file", "give a packing file, or --rcp with a distribution");
  const Packing p = read_packing(o.file, Isolation::child_process, kIsolatedReadBaseSeconds, o.frame);
  if (o.d_given) check_file_dimension(p.d, o.spec.d, o.file);
  const auto dist = recorded_distribution(p);
  const PackingQuality q = assess_packing(p, dist.get());
  std::cout << (o.json ? packing_report_json(o.file, p, q, dist != nullptr)
                       : packing_report_text(o.file, p, q, dist != nullptr));
}

}  // namespace

void register_info_command(CLI::App& app) {
  auto o = std::make_shared<InfoOptions>();
  auto* sub = app.add_subcommand("info", "quality of a packing file, or --rcp: random close packing estimate");
  sub->add_option("file", o->file, "packing file (HDF5, CSV/text, LAMMPS data or dump, MercuryDPM .data or .restart)");
  add_frame_option(sub, o->frame);
  sub->add_flag("--json", o->json, "JSON output");
  sub->add_flag("--rcp", o->rcp, "print the random close packing estimate of a distribution");
  auto* d = sub->add_option("--d", o->spec.d, "--rcp: dimension; with a file: checked against the file's")->default_val(3);
  sub->add_option("--dist", o->spec.dist, "--rcp: powerlaw|lognormal")->default_val("powerlaw");
  sub->add_option("--alpha", o->spec.alpha, "--rcp: power-law exponent")->default_val(-3.0);
  sub->add_option("--omega", o->spec.omega, "--rcp: size ratio")->default_val(100.0);
  sub->add_option("--sigma", o->spec.sigma, "--rcp: lognormal sigma")->default_val(0.5);
  sub->callback([o, d] {
    o->d_given = d->count() > 0;
    run_info(*o);
  });
}

}  // namespace hgrid::cli
