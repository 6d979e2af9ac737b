#include "hgridlab/advice/recommend_json.hpp"

#include <nlohmann/json.hpp>

#include "hgridlab/io/peer_settings.hpp"

namespace hgrid {

std::string recommendation_json(const Recommendation& r, const KChoice& k, Search search, double skin) {
  nlohmann::json j;
  j["r_min"] = r.r_min;
  j["r_max"] = r.r_max;
  j["omega"] = r.r_max / r.r_min;
  j["K"] = k.K;
  j["K_source"] = to_string(k.source);
  j["calibration_path"] = k.calibration_path;
  j["K_note"] = k.note;
  j["search"] = to_string(search);
  j["levels"] = r.levels();
  j["sizes"] = r.sizes;
  j["sizes_pasted"] = rounded_up_sizes(r.sizes);
  j["fraction_per_level"] = r.model.P;
  j["particles_per_cell"] = r.model.m;
  j["T_over_N"] = r.model.T_over_N;
  j["T_cd_over_N"] = r.model.T_cd_over_N;
  j["T_ca_over_N"] = r.model.T_ca_over_N;
  j["linked_cell_size"] = r.linked_cell_size;
  j["tilt_inflation"] = r.tilt_inflation;
  j["linked_cell_T_over_N"] = r.linked_cell.T_over_N;
  j["speedup"] = r.speedup();
  j["cost"] = r.seconds ? "time" : "count";
  j["predicted_seconds_build"] = r.seconds ? nlohmann::json(r.seconds->build) : nlohmann::json();
  j["predicted_seconds_query"] = r.seconds ? nlohmann::json(r.seconds->query) : nlohmann::json();
  j["linked_cell_predicted_seconds"] = r.seconds ? nlohmann::json(r.linked_cell_seconds->total()) : nlohmann::json();
  j["speedup_seconds"] = r.seconds ? nlohmann::json(r.speedup_seconds()) : nlohmann::json();
  j["lammps_collections"] = r.lammps_collections;
  j["lammps_model"] = r.lammps_model_source;
  j["lammps"] = lammps_settings(r.lammps_collections, skin);
  j["mercurydpm"] = mercurydpm_settings(r.sizes, search);
  if (r.field) {
    const FieldUse& f = *r.field;
    j["field"] = {{"window", f.summary.window},
                  {"box_nu", f.summary.box_nu},
                  {"mean_local_nu", f.summary.mean_nu},
                  {"effective_nu", f.nu_effective},
                  {"empty_fraction", f.summary.empty_fraction},
                  {"histogram", f.summary.histogram},
                  {"far_from_homogeneous", f.far_from_homogeneous()},
                  {"sizes_from", f.sizes_from_field() ? "field" : "box"},
                  {"homogeneous_T_over_N", f.homogeneous_T_over_N},
                  {"homogeneous_sizes", f.homogeneous_sizes},
                  {"homogeneous_sizes_T_over_N", f.homogeneous_sizes_T_over_N}};
  } else {
    j["field"] = nullptr;
  }
  return j.dump();
}

}  // namespace hgrid
