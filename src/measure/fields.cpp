#include "hgridlab/measure/fields.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace hgrid {
namespace {

FieldValue num(double v) { return std::isfinite(v) ? FieldValue(v) : FieldValue(std::monostate{}); }
FieldValue text(const std::string& s) { return s.empty() ? FieldValue(std::monostate{}) : FieldValue(s); }
FieldValue whole(std::uint64_t v) { return FieldValue(v); }
template <class T>
FieldValue list(const std::vector<T>& v) {
  return v.empty() ? FieldValue(std::monostate{}) : FieldValue(v);
}

using M = Measurement;
// clang-format off
const MeasurementField kFields[] = {
  {"n", "1", "particles", [](const M& m) { return whole(m.n); }},
  {"d", "1", "dimension (2: discs, 3: spheres)", [](const M& m) { return FieldValue(std::int64_t{m.d}); }},
  {"boundary", "", "periodic or walls", [](const M& m) { return FieldValue(std::string(to_string(m.boundary))); }},
  {"boundary_source", "", "file, or 'assumed: not in the file' (periodic)",
   [](const M& m) { return FieldValue(std::string(m.boundary_assumed ? "assumed: not in the file" : "file")); }},
  {"nu_achieved", "1", "packing fraction of the particles in their box", [](const M& m) { return num(m.nu_achieved); }},
  {"tilt", "length", "a tilted (triclinic) periodic box's tilts: xy (2D), xy xz yz (3D); null: orthogonal",
   [](const M& m) { return list(m.tilt); }},
  {"tilt_inflation", "1", "c: a tilted box's grid searches spheres and cells c times larger in the mapped box (docs/MODEL.md section 12)",
   [](const M& m) { return num(m.tilt_inflation); }},
  {"search", "", "cross-level search: topdown or bottomup", [](const M& m) { return FieldValue(std::string(to_string(m.search))); }},
  {"threads", "1", "threads the counted search ran on (the counts do not depend on it)",
   [](const M& m) { return FieldValue(std::int64_t{m.threads}); }},
  {"K", "1", "weight of a cell access in T = narrow-phase checks + K cell accesses (Eq. 27)", [](const M& m) { return num(m.K); }},
  {"sizes_requested", "length", "cell sizes asked for, per level", [](const M& m) { return list(m.sizes_requested); }},
  {"sizes", "length", "cell sizes the grid used (equal ones merged; fitted to a periodic box)", [](const M& m) { return list(m.sizes); }},
  {"levels", "1", "L, levels the grid used", [](const M& m) { return FieldValue(std::int64_t{m.counts.levels}); }},
  {"cell_accesses", "1", "T_ca: cells visited by the search (Eq. 12-16)", [](const M& m) { return whole(m.counts.cell_accesses); }},
  {"narrow_phase_checks", "1", "T_cd: sphere-sphere overlap tests (Eq. 17-22)", [](const M& m) { return whole(m.counts.narrow_phase_checks); }},
  {"contacts", "1", "overlapping pairs found", [](const M& m) { return whole(m.counts.contacts); }},
  {"particles_per_level", "1", "particles in each level (L)", [](const M& m) { return list(m.counts.particles_per_level); }},
  {"accesses_by_level", "1", "cell accesses, L x L row-major: level of the particle, level searched",
   [](const M& m) { return list(m.counts.accesses_by_level); }},
  {"checks_by_level", "1", "narrow-phase checks, L x L like accesses_by_level", [](const M& m) { return list(m.counts.checks_by_level); }},
  {"T_over_N", "1", "T / N = (checks + K accesses) / n", [](const M& m) { return num(m.T_over_N); }},
  {"T_cd_over_N", "1", "narrow-phase checks / n", [](const M& m) { return num(m.T_cd_over_N); }},
  {"T_ca_over_N", "1", "cell accesses / n", [](const M& m) { return num(m.T_ca_over_N); }},
  {"model_T_over_N", "1", "the paper's model (random centres) for the same radii, nu and sizes", [](const M& m) { return num(m.model_T_over_N); }},
  {"model_T_cd_over_N", "1", "its checks / n", [](const M& m) { return num(m.model_T_cd_over_N); }},
  {"model_T_ca_over_N", "1", "its cell accesses / n", [](const M& m) { return num(m.model_T_ca_over_N); }},
  {"model_checks_by_level", "1", "its expected checks, L x L like checks_by_level", [](const M& m) { return list(m.model_checks_by_level); }},
  {"model_skipped", "", "why the random-centres model was not computed (when asked)", [](const M& m) { return text(m.model_skipped); }},
  {"model_excluded_T_over_N", "1", "the excluded-volume model (hard spheres; docs/MODEL.md section 8)",
   [](const M& m) { return num(m.model_excluded_T_over_N); }},
  {"model_excluded_T_cd_over_N", "1", "its checks / n", [](const M& m) { return num(m.model_excluded_T_cd_over_N); }},
  {"model_excluded_T_ca_over_N", "1", "its cell accesses / n", [](const M& m) { return num(m.model_excluded_T_ca_over_N); }},
  {"model_excluded_checks_by_level", "1", "its expected checks, L x L like checks_by_level",
   [](const M& m) { return list(m.model_excluded_checks_by_level); }},
  {"model_excluded_skipped", "", "why the excluded-volume model was not computed", [](const M& m) { return text(m.model_excluded_skipped); }},
  {"wall_pairs", "", "walls: the excluded-volume model's pairs near a wall (layer or product)",
   [](const M& m) { return m.wall_pairs ? FieldValue(std::string(to_string(*m.wall_pairs))) : FieldValue(std::monostate{}); }},
  {"share_multi_lowest", "1", "lowest-level cells holding >= 2 particles / its occupied and empty cells",
   [](const M& m) { return num(m.share_multi_lowest); }},
  {"seconds_build", "s", "wall time of the counted search's build", [](const M& m) { return num(m.seconds_build); }},
  {"seconds_query", "s", "wall time of the counted search", [](const M& m) { return num(m.seconds_query); }},
  {"repeats", "1", "uncounted build + search runs timed", [](const M& m) { return FieldValue(std::int64_t{m.repeats}); }},
  {"seconds_build_best", "s", "fastest uncounted build", [](const M& m) { return num(m.seconds_build_best); }},
  {"seconds_query_best", "s", "fastest uncounted search (what a simulation runs)", [](const M& m) { return num(m.seconds_query_best); }},
  {"seconds_query_median", "s", "median uncounted search", [](const M& m) { return num(m.seconds_query_median); }},
  {"time_model", "", "the calibration the predicted seconds come from", [](const M& m) { return text(m.time_model); }},
  {"predicted_seconds_build_one_thread", "s", "the time model's build on one thread (expected terms for the sizes used)",
   [](const M& m) { return num(m.predicted_seconds_build_one_thread); }},
  {"predicted_seconds_query_one_thread", "s", "the time model's search on one thread (expected terms)",
   [](const M& m) { return num(m.predicted_seconds_query_one_thread); }},
  {"predicted_seconds_build_one_thread_from_counts", "s", "the same from the terms this build counted",
   [](const M& m) { return num(m.predicted_seconds_build_one_thread_from_counts); }},
  {"predicted_seconds_query_one_thread_from_counts", "s", "the same from the terms this search counted",
   [](const M& m) { return num(m.predicted_seconds_query_one_thread_from_counts); }},
};
// clang-format on

nlohmann::ordered_json to_json(const FieldValue& v) {
  return std::visit(
      [](const auto& x) -> nlohmann::ordered_json {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, std::monostate>)
          return nullptr;
        else
          return x;
      },
      v);
}

}  // namespace

std::span<const MeasurementField> measurement_fields() { return kFields; }

const MeasurementField& measurement_field(std::string_view name) {
  for (const auto& f : kFields)
    if (name == f.name) return f;
  throw std::logic_error("measurement_field: no field '" + std::string(name) + "'");
}

std::string measurement_json(const Measurement& m, std::span<const std::string_view> names, int indent) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& f : kFields)
    if (names.empty() || std::find(names.begin(), names.end(), std::string_view(f.name)) != names.end())
      j[f.name] = to_json(f.value(m));
  for (const auto& n : names) (void)measurement_field(n);  // every name asked for exists
  return j.dump(indent);
}

namespace {
void append(std::string& out, const char* fmt, ...) __attribute__((format(printf, 2, 3)));
void append(std::string& out, const char* fmt, ...) {
  char buf[512];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  out += buf;
}
}  // namespace

std::string measurement_text(const Measurement& m) {
  const auto g6 = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return std::string(b);
  };
  std::string s;
  append(s, "n = %llu, d = %d, %s%s, nu = %.6g, search %s, K = %g\n", (unsigned long long)m.n, m.d,
         to_string(m.boundary), m.boundary_assumed ? " (not in the file: assumed)" : "", m.nu_achieved,
         to_string(m.search), m.K);
  if (!m.tilt.empty())
    append(s, "tilted box: %s = %s, grid on the mapped spheres (radii and cell sizes x c = %.6g)\n",
           m.tilt.size() == 1 ? "xy" : "xy xz yz",
           m.tilt.size() == 1 ? std::to_string(m.tilt[0]).c_str()
                              : (std::to_string(m.tilt[0]) + " " + std::to_string(m.tilt[1]) + " " + std::to_string(m.tilt[2])).c_str(),
           m.tilt_inflation);
  const bool ex = !m.model_excluded_checks_by_level.empty();
  const auto L = static_cast<std::size_t>(m.counts.levels);
  const auto row_sum = [L](const auto& v, std::size_t h) {
    double sum = 0;
    for (std::size_t k = 0; k < L && h * L + k < v.size(); ++k) sum += static_cast<double>(v[h * L + k]);
    return sum;
  };
  // The models' columns: expected narrow-phase checks of the level's particles.
  append(s, "%5s %14s %12s %16s %20s %14s %16s\n", "level", "size", "particles", "cell_accesses",
         "narrow_phase_checks", "model_checks", "excluded_checks");
  for (std::size_t h = 0; h < L; ++h)
    append(s, "%5zu %14.6g %12llu %16.0f %20.0f %14s %16s\n", h + 1, m.sizes[h],
           (unsigned long long)m.counts.particles_per_level[h], row_sum(m.counts.accesses_by_level, h),
           row_sum(m.counts.checks_by_level, h),
           m.model_checks_by_level.empty() ? "-" : g6(row_sum(m.model_checks_by_level, h)).c_str(),
           ex ? std::to_string(row_sum(m.model_excluded_checks_by_level, h)).c_str() : "-");
  append(s, "total: %llu cell accesses, %llu narrow-phase checks, %llu contacts, T/N = %.6g\n",
         (unsigned long long)m.counts.cell_accesses, (unsigned long long)m.counts.narrow_phase_checks,
         (unsigned long long)m.counts.contacts, m.T_over_N);
  if (std::isfinite(m.model_T_over_N)) {
    append(s, "model T/N = %.6g (random centres)", m.model_T_over_N);
    if (ex)
      append(s, ", %.6g (excluded volume)\n", m.model_excluded_T_over_N);
    else
      append(s, "; excluded-volume model: %s\n", m.model_excluded_skipped.empty() ? "not asked" : m.model_excluded_skipped.c_str());
  }
  if (!m.model_skipped.empty()) append(s, "model: not computed: %s\n", m.model_skipped.c_str());
  if (m.repeats > 0)
    append(s, "wall time, fastest of %d uncounted runs on %d threads: query %.6g s, build %.6g s\n", m.repeats,
           m.threads, m.seconds_query_best, m.seconds_build_best);
  if (!m.time_model.empty())
    append(s, "time model (%s), one thread: query %.6g s, build %.6g s (from the counts: %.6g s, %.6g s)\n",
           m.time_model.c_str(), m.predicted_seconds_query_one_thread, m.predicted_seconds_build_one_thread,
           m.predicted_seconds_query_one_thread_from_counts, m.predicted_seconds_build_one_thread_from_counts);
  return s;
}

}  // namespace hgrid
