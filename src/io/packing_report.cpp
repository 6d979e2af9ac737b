#include "hgridlab/io/packing_report.hpp"

#include <nlohmann/json.hpp>
#include <sstream>

#include "hgridlab/grid/tilted_box.hpp"
#include "hgridlab/io/particle_file.hpp"

namespace hgrid {

std::string packing_report_json(const std::string& file, const Packing& p, const PackingQuality& q,
                                bool recorded_distribution) {
  nlohmann::json j;
  j["file"] = file;
  j["n"] = p.size();
  j["d"] = p.d;
  j["box"] = std::vector<double>(p.box.begin(), p.box.begin() + p.d);
  j["tilt"] = p.tilted() ? nlohmann::json(tilt_values(p.tilt, p.d)) : nlohmann::json();
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
  if (recorded_distribution) {
    j["ks_distance"] = q.ks_distance;
    j["ks_pvalue"] = q.ks_pvalue;
    j["radius_histogram"] = {{"edges", q.hist_edges}, {"count", q.hist_count}, {"expected", q.hist_expected}};
  }
  nlohmann::json attrs;
  for (const auto& [k, v] : p.num_attrs) attrs[k] = v;
  for (const auto& [k, v] : p.str_attrs) attrs[k] = v;
  j["attributes"] = attrs;
  return j.dump(2) + "\n";
}

std::string packing_report_text(const std::string& file, const Packing& p, const PackingQuality& q,
                                bool recorded_distribution) {
  std::ostringstream out;
  out << file << ": n = " << p.size() << ", d = " << p.d << ", " << boundary_description(p) << ", nu = " << q.nu
      << "\n  max / mean relative overlap: " << q.max_rel_overlap << " / " << q.mean_rel_overlap
      << "\n  mean contact number: " << q.mean_contacts << "\n  slab nu, worst relative deviation: " << q.slab_max_dev
      << " (counting noise alone: " << q.slab_noise << ")\n  per size band (equal volume shares):";
  for (std::size_t b = 0; b < q.band_slab_max_dev.size(); ++b)
    out << " " << q.band_slab_max_dev[b] << " (noise " << q.band_slab_noise[b] << ")";
  out << "\n";
  if (recorded_distribution) out << "  radii vs pdf: KS distance " << q.ks_distance << ", p = " << q.ks_pvalue << "\n";
  return out.str();
}

}  // namespace hgrid
