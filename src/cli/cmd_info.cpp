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
  nlohmann::json j;
  j["file"] = o.file;
  j["n"] = p.size();
  j["d"] = p.d;
  j["box"] = std::vector<double>(p.box.begin(), p.box.begin() + p.d);
  j["tilt"] = p.tilted() ? nlohmann::json(tilt_values(p.tilt, p.d))
                         : nlohmann::json();
  j["boundary"] = to_string(p.boundary);
  j["nu"] = q.nu;
  j["max_rel_overlap"] = q.max_rel_overlap;
  j["mean_rel_overlap"] = q.mean_rel_overlap;
  j["overlapping_pairs"] = q.overlapping_pairs;
  j["mean_contacts"] = q.mean_contacts;
  j["contact_gap"] = kContactGap;
  j["slab_nu"] = q.slab_nu;
  j["slab_max_rel_dev"] = q.slab_max_dev;
  j["size_band_slab_max_rel_dev"] = q.band_slab_max_dev;
  j["slab_counting_noise"] = q.slab_noise;
  j["size_band_slab_counting_noise"] = q.band_slab_noise;
  if (dist) {
    j["ks_distance"] = q.ks_distance;
    j["ks_pvalue"] = q.ks_pvalue;
    j["radius_histogram"] = {{"edges", q.hist_edges}, {"count", q.hist_count}, {"expected", q.hist_expected}};
  }
  nlohmann::json attrs;
  for (const auto& [k, v] : p.num_attrs) attrs[k] = v;
  for (const auto& [k, v] : p.str_attrs) attrs[k] = v;
  j["attributes"] = attrs;
  if (o.json) {
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cout << o.file << ": n = " << p.size() << ", d = " << p.d << ", " << boundary_description(p) << ", nu = " << q.nu
            << "\n  max / mean relative overlap: " << q.max_rel_overlap << " / " << q.mean_rel_overlap
            << "\n  mean contact number: " << q.mean_contacts << "\n  slab nu, worst relative deviation: "
            << q.slab_max_dev << " (counting noise alone: " << q.slab_noise << ")\n  per size band (equal volume shares):";
  for (std::size_t b = 0; b < q.band_slab_max_dev.size(); ++b)
    std::cout << " " << q.band_slab_max_dev[b] << " (noise " << q.band_slab_noise[b] << ")";
  std::cout << "\n";
  if (dist) std::cout << "  radii vs pdf: KS distance " << q.ks_distance << ", p = " << q.ks_pvalue << "\n";
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
