#include "hgridlab/scenes/detail/results.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "hgridlab/grid/params.hpp"
#include "hgridlab/packing/generate.hpp"
#include "hgridlab/packing/packing.hpp"
#include "hgridlab/io/provenance.hpp"
#include "hgridlab/io/result_table.hpp"
#include "hgridlab/measure/fields.hpp"

namespace hgrid {
namespace {
/// The measurement's fields a scene records (measure/fields.hpp names them).
constexpr std::string_view kMeasuredFields[] = {
    "n", "search", "levels", "sizes", "nu_achieved", "cell_accesses", "narrow_phase_checks", "contacts",
    "particles_per_level", "accesses_by_level", "checks_by_level", "T_over_N", "T_cd_over_N", "T_ca_over_N",
    "model_T_over_N", "model_T_cd_over_N", "model_T_ca_over_N", "model_excluded_T_over_N",
    "model_excluded_T_cd_over_N", "model_excluded_T_ca_over_N", "share_multi_lowest", "seconds_build",
    "seconds_query"};
}  // namespace

nlohmann::json detail::result_to_json(const PointResult& r) {
  const PackingSpec& s = r.point.packing;
  nlohmann::json j = nlohmann::json::parse(measurement_json(r.m, kMeasuredFields, -1));
  j.update({{"d", s.d},
            {"nu", s.nu},
            {"dist", s.dist},
            {"alpha", s.alpha},
            {"omega", s.omega},
            {"sigma", s.sigma},
            {"boundary", to_string(s.boundary)},
            {"placement", to_string(s.placement)},
            {"method", to_string(s.method)},
            {"seed", s.seed},
            {"equilibrate", s.equilibrate},
            {"sweeps", s.sweeps},
            {"stop", to_string(s.stop)},
            {"moves", to_string(s.moves)},
            {"stationary_tol", s.stationary_tol},
            {"equilibration_sweeps", r.equilibration_sweeps},
            {"seconds_packing", r.seconds_packing},
            {"seconds_sizes", r.seconds_sizes}});
  return j;
}

namespace {

// Typed reads of a journal line: every value is checked like any input
// (type, sign, range), never trusted as written.
const nlohmann::json& field(const nlohmann::json& j, const char* key) {
  if (!j.is_object() || !j.contains(key)) throw InputError(key, "missing");
  return j.at(key);
}
std::uint64_t count_of(const nlohmann::json& j, const char* key) {
  const auto& v = field(j, key);
  if (!v.is_number_unsigned()) throw InputError(key, "must be a whole number >= 0");
  return v.get<std::uint64_t>();
}
double finite_of(const nlohmann::json& j, const char* key) {
  const auto& v = field(j, key);
  if (!v.is_number() || !std::isfinite(v.get<double>())) throw InputError(key, "must be a finite number");
  return v.get<double>();
}
double optional_of(const nlohmann::json& j, const char* key) {  // null: not recorded
  return field(j, key).is_null() ? std::nan("") : finite_of(j, key);
}
std::string text_of(const nlohmann::json& j, const char* key) {
  const auto& v = field(j, key);
  if (!v.is_string()) throw InputError(key, "must be a string");
  return v.get<std::string>();
}
/// A list of at most max_size counts (L per level, or L x L by level pairs).
std::vector<std::uint64_t> counts_of(const nlohmann::json& j, const char* key, std::size_t max_size) {
  const auto& v = field(j, key);
  if (!v.is_array() || v.size() > max_size) throw InputError(key, "must be a list of counts");
  std::vector<std::uint64_t> out;
  for (const auto& e : v) {
    if (!e.is_number_unsigned()) throw InputError(key, "must be a list of whole numbers >= 0");
    out.push_back(e.get<std::uint64_t>());
  }
  return out;
}

}  // namespace

PointResult detail::result_from_json(const nlohmann::json& j) {
  PointResult r;
  PackingSpec& s = r.point.packing;
  s.d = static_cast<int>(count_of(j, "d"));
  s.n = count_of(j, "n");
  s.nu = finite_of(j, "nu");
  s.dist = text_of(j, "dist");
  s.alpha = finite_of(j, "alpha");
  s.omega = finite_of(j, "omega");
  s.sigma = finite_of(j, "sigma");
  s.boundary = parse_boundary(text_of(j, "boundary"));
  s.placement = parse_placement(text_of(j, "placement"));
  // Journals written before the placement method was a parameter have none.
  if (j.contains("method")) s.method = parse_excluded_method(text_of(j, "method"));
  s.seed = count_of(j, "seed");
  if (!field(j, "equilibrate").is_boolean()) throw InputError("equilibrate", "must be true or false");
  s.equilibrate = field(j, "equilibrate").get<bool>();
  // Journals written before the Monte Carlo sweeps were a parameter have none.
  if (j.contains("sweeps")) {
    const auto sweeps = count_of(j, "sweeps");
    if (sweeps < 1 || sweeps > static_cast<std::uint64_t>(kMaxEquilibrationSweeps))
      throw InputError("sweeps", "must be in [1, " + std::to_string(kMaxEquilibrationSweeps) + "]");
    s.sweeps = static_cast<int>(sweeps);
  }
  // Journals written before an equilibration could stop when stationary have
  // neither: all its sweeps were run.
  if (j.contains("stop")) s.stop = parse_equilibration_stop(text_of(j, "stop"));
  // Journals written before event chains have the checkerboard's moves.
  if (j.contains("moves")) s.moves = parse_equilibration_moves(text_of(j, "moves"));
  if (j.contains("stationary_tol")) {
    if (!field(j, "stationary_tol").is_number()) throw InputError("stationary_tol", "must be a number");
    s.stationary_tol = field(j, "stationary_tol").get<double>();
  }
  if (j.contains("equilibration_sweeps")) {
    r.equilibration_sweeps = count_of(j, "equilibration_sweeps");
    if (r.equilibration_sweeps > (s.equilibrate ? static_cast<std::uint64_t>(s.sweeps) : 0))
      throw InputError("equilibration_sweeps", "must be at most the sweeps asked (0 without equilibrate)");
  } else {
    r.equilibration_sweeps = s.equilibrate ? static_cast<std::uint64_t>(s.sweeps) : 0;
  }
  r.point.search = parse_search(text_of(j, "search"));
  Measurement& m = r.m;
  m.d = s.d;
  m.boundary = s.boundary;
  m.search = r.point.search;
  m.n = count_of(j, "n");
  m.nu_achieved = finite_of(j, "nu_achieved");
  const auto& sizes = field(j, "sizes");
  if (!sizes.is_array()) throw InputError("sizes", "must be a list of numbers");
  for (const auto& e : sizes) {
    if (!e.is_number() || !std::isfinite(e.get<double>())) throw InputError("sizes", "must be finite numbers");
    m.sizes.push_back(e.get<double>());
  }
  Counters& c = m.counts;
  c.levels = static_cast<int>(count_of(j, "levels"));
  c.cell_accesses = count_of(j, "cell_accesses");
  c.narrow_phase_checks = count_of(j, "narrow_phase_checks");
  c.contacts = count_of(j, "contacts");
  constexpr auto kLevels = static_cast<std::size_t>(kMaxLevels);
  c.particles_per_level = counts_of(j, "particles_per_level", kLevels);
  c.accesses_by_level = counts_of(j, "accesses_by_level", kLevels * kLevels);
  c.checks_by_level = counts_of(j, "checks_by_level", kLevels * kLevels);
  m.T_over_N = finite_of(j, "T_over_N");
  m.T_cd_over_N = finite_of(j, "T_cd_over_N");
  m.T_ca_over_N = finite_of(j, "T_ca_over_N");
  m.model_T_over_N = optional_of(j, "model_T_over_N");
  m.model_T_cd_over_N = optional_of(j, "model_T_cd_over_N");
  m.model_T_ca_over_N = optional_of(j, "model_T_ca_over_N");
  // Absent in journals written before the excluded-volume model: not recorded.
  for (auto [key, dst] : {std::pair{"model_excluded_T_over_N", &m.model_excluded_T_over_N},
                          std::pair{"model_excluded_T_cd_over_N", &m.model_excluded_T_cd_over_N},
                          std::pair{"model_excluded_T_ca_over_N", &m.model_excluded_T_ca_over_N}})
    *dst = j.is_object() && j.contains(key) ? optional_of(j, key) : std::nan("");
  m.share_multi_lowest = optional_of(j, "share_multi_lowest");
  r.seconds_packing = finite_of(j, "seconds_packing");
  r.seconds_sizes = finite_of(j, "seconds_sizes");
  m.seconds_build = finite_of(j, "seconds_build");
  m.seconds_query = finite_of(j, "seconds_query");
  return r;
}

void detail::check_result(const PointResult& r, double K) {
  const Measurement& m = r.m;
  const Counters& c = m.counts;
  const auto L = static_cast<std::size_t>(c.levels);
  // Sizes and particles per level; accesses and checks per pair of levels
  // (particle's level x level searched, Counters).
  if (c.levels < 1 || m.sizes.size() != L || c.particles_per_level.size() != L ||
      c.accesses_by_level.size() != L * L || c.checks_by_level.size() != L * L)
    throw InputError("levels", "the per-level lists do not have one entry per level (L x L by level pairs)");
  std::uint64_t n = 0, acc = 0, chk = 0;
  for (std::uint64_t v : c.particles_per_level) n += v;
  for (std::uint64_t v : c.accesses_by_level) acc += v;
  for (std::uint64_t v : c.checks_by_level) chk += v;
  if (n != m.n || m.n != r.point.packing.n) throw InputError("particles_per_level", "does not add up to n");
  if (acc != c.cell_accesses) throw InputError("accesses_by_level", "does not add up to cell_accesses");
  if (chk != c.narrow_phase_checks) throw InputError("checks_by_level", "does not add up to narrow_phase_checks");
  if (c.contacts > c.narrow_phase_checks) throw InputError("contacts", "more contacts than checks");
  if (m.T_over_N != c.cost(K) / static_cast<double>(m.n)) throw InputError("T_over_N", "is not (checks + K accesses) / n");
}

namespace {

/// Columns of the CSV summary (also the 1-D datasets of the HDF5 file).
const char* const kNumericColumns[] = {"d", "n", "nu", "nu_achieved", "alpha", "omega", "sigma", "seed",
                                       "equilibration_sweeps", "levels",
                                       "cell_accesses", "narrow_phase_checks", "contacts", "T_over_N", "T_cd_over_N",
                                       "T_ca_over_N", "model_T_over_N", "model_T_cd_over_N", "model_T_ca_over_N",
                                       "model_excluded_T_over_N", "model_excluded_T_cd_over_N",
                                       "model_excluded_T_ca_over_N",
                                       "share_multi_lowest", "seconds_packing", "seconds_sizes", "seconds_build",
                                       "seconds_query"};
const char* const kTextColumns[] = {"dist", "boundary", "placement", "method", "search"};

}  // namespace

std::string result_json_line(const PointResult& r) { return detail::result_to_json(r).dump(); }

PointResult result_from_json_line(const std::string& line, double K) {
  PointResult r = detail::result_from_json(nlohmann::json::parse(line));
  r.m.K = K;
  detail::check_result(r, K);
  return r;
}

void write_results(const std::string& stem, const Scene& scene, const std::vector<PointResult>& results) {
  std::vector<nlohmann::json> rows;
  std::size_t lmax = 0;
  for (const auto& r : results) {
    rows.push_back(detail::result_to_json(r));
    lmax = std::max<std::size_t>(lmax, r.m.counts.levels);
  }
  ResultTable t;
  for (const char* c : kTextColumns) {
    std::vector<std::string> v;
    for (const auto& j : rows) v.push_back(j.at(c));
    t.columns.push_back({c, std::move(v)});
  }
  for (const char* c : kNumericColumns) {
    std::vector<double> v;
    for (const auto& j : rows) v.push_back(j.at(c).is_null() ? std::nan("") : j.at(c).get<double>());
    t.columns.push_back({c, std::move(v)});
  }
  // The sizes: in the CSV one column "s0;s1;...", in the HDF5 file the
  // [point][level] array below.
  std::vector<std::string> sizes_text;
  for (const auto& j : rows) {
    std::ostringstream out;
    out.precision(t.csv_precision);
    bool first = true;
    for (double s : j.at("sizes")) out << (first ? "" : ";") << s, first = false;
    sizes_text.push_back(out.str());
  }
  t.columns.push_back({"sizes", std::move(sizes_text), true, false});
  // Per level (padded: NaN sizes, zero counts beyond a point's own L).
  const std::size_t P = rows.size(), L = lmax;
  std::vector<double> sizes(P * L, std::nan(""));
  std::vector<std::uint64_t> particles(P * L, 0), acc(P * L * L, 0), chk(P * L * L, 0);
  for (std::size_t i = 0; i < results.size(); ++i) {
    const Measurement& r = results[i].m;
    const std::size_t l = r.counts.levels;
    for (std::size_t h = 0; h < l; ++h) {
      sizes[i * L + h] = r.sizes[h];
      particles[i * L + h] = r.counts.particles_per_level[h];
      for (std::size_t k = 0; k < l; ++k) {
        acc[(i * L + h) * L + k] = r.counts.accesses_by_level[h * l + k];
        chk[(i * L + h) * L + k] = r.counts.checks_by_level[h * l + k];
      }
    }
  }
  t.arrays = {{"sizes", std::move(sizes), {P, L}},
              {"particles_per_level", std::move(particles), {P, L}},
              {"accesses_by_level", std::move(acc), {P, L, L}},
              {"checks_by_level", std::move(chk), {P, L, L}}};
  t.attributes = {{"scene", scene.name},
                  {"description", scene.description},
                  {"scale", scene.scale},
                  {"scene_toml", scene.source},
                  {"cells", std::string(to_string(scene.grid.cells))},
                  {"K", std::vector<double>{scene.grid.K}},
                  {"q", std::vector<double>{scene.grid.q}},
                  {"levels_requested", std::vector<double>{scene.grid.levels ? *scene.grid.levels : 0.0}}};
  for (const auto& [k, v] : provenance_fields()) t.attributes.emplace_back(k, v);
  t.attributes.emplace_back("created_utc", utc_now());
  t.attributes.emplace_back("matrix_layout", std::string("[point][level of the particle][level searched]"));
  t.csv_comments = {"scene=" + scene.name + " scale=" + scene.scale + " " + provenance_line()};
  write_result_table(stem, t);
}

}  // namespace hgrid
