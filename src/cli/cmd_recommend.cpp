// hgrid recommend FILE: the cost model's cell sizes for one's own particles,
// in the file's unit, with the predicted speed-up over the linked cell and
// settings to paste into LAMMPS and MercuryDPM (docs/RECOMMEND.md).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "common.hpp"
#include "hgridlab/calibration/calibration.hpp"
#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/calibration/k_choice.hpp"
#include "hgridlab/advice/recommend.hpp"
#include "hgridlab/advice/recommend_json.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/io/particle_file.hpp"
#include "hgridlab/io/peer_settings.hpp"

namespace hgrid::cli {
namespace {

struct RecommendOptions {
  std::string file, K, search = "topdown", cost = "auto";
  std::optional<std::int64_t> frame;
  std::string frames;  // FIRST:LAST, the snapshots the sizes are chosen over
  std::string boundary;  // for a file that does not say its own
  std::optional<double> nu;
  std::optional<int> d;
  double skin = 0;
  bool json = false, homogeneous = false;
};

/// Every key of --json, for --help and docs/RECOMMEND.md.
constexpr const char* kJsonKeys =
    "--json keys: file, format (hdf5|table|lammps_data|lammps_dump|mercury_data|mercury_restart), frames ([first, last] "
    "snapshot used), n (with --frames: particles over all snapshots), d, r_min, r_max, omega (r_max/r_min), "
    "nu (the homogeneous nu the sizes were chosen for: with a field, its effective nu), nu_source (field|box|given), field (null "
    "without positions: window, box_nu, mean_local_nu, effective_nu, empty_fraction, histogram (fraction of particles per local nu "
    "bin of 0.05), far_from_homogeneous, homogeneous_T_over_N (the box's nu at these sizes), homogeneous_sizes (what the box's nu "
    "alone recommends), homogeneous_sizes_T_over_N (the field model's T/N for them), sizes_from (field: far from homogeneous; "
    "box: the homogeneous sizes)), box (side lengths or null), tilt (a tilted box's xy [xz yz], or null), tilt_inflation (c: a tilted box's grid searches the mapped packing, radii and sizes x c, at c^d nu; 1 untilted), boundary, K, K_source (given|calibration|paper), "
    "calibration_path, K_note (why a stored calibration was not used, or empty), search, levels, sizes (exact cell sizes, file's unit), sizes_pasted (rounded up to 6 digits, "
    "as in the settings), fraction_per_level, particles_per_cell, T_over_N, T_cd_over_N (overlap tests), "
    "T_ca_over_N (cell accesses), linked_cell_size (2 r_max), linked_cell_T_over_N, speedup "
    "(linked_cell_T_over_N / T_over_N), cost (count|time: what the sizes minimise), predicted_seconds_build, "
    "predicted_seconds_query, linked_cell_predicted_seconds (build + query), speedup_seconds (the last four: "
    "this machine's time model, null with cost count), lammps_collections (LAMMPS multi collection bounds, exact: "
    "from LAMMPS's own cost model, not the HGrid sizes), lammps_model (default, or the fit.json "
    "$HGRID_LAMMPS_MODEL names), lammps (input lines), mercurydpm (code lines). "
    "T = tests + K accesses.";

std::string k_text(const KChoice& k) {
  switch (k.source) {
    case KSource::given: return "given";
    case KSource::calibration: return "this machine's calibration, " + k.calibration_path;
    case KSource::paper:
      if (!k.note.empty()) return "the paper's value; the stored calibration was not used: " + k.note;
      return "the paper's value; no calibration at " + k.calibration_path + "; `hgrid calibrate` measures one";
  }
  return "";
}

void print_text(const RecommendOptions& o, const ParticleSet& s, const FileInputs& in, const KChoice& k,
                const Recommendation& r, Search search, std::size_t first, std::size_t last) {
  const std::string snapshot =
      first != last ? ", snapshots " + std::to_string(first) + " to " + std::to_string(last) + " of " +
                          std::to_string(s.frames) + " (particles counted in each)"
      : s.frames > 1 ? ", snapshot " + std::to_string(s.frame) + " of " + std::to_string(s.frames)
                     : std::string();
  std::printf("%s: %zu particles (%s, %dD%s), r_min = %g, r_max = %g (omega = %g)\n", o.file.c_str(), s.size(),
              to_string(s.format), in.d, snapshot.c_str(), r.r_min, r.r_max, r.r_max / r.r_min);
  if (r.field) {
    const FieldUse& f = *r.field;
    std::printf("nu = %.4g over the box (boundary %s); the particles' own: local nu in windows of side %.4g (3 x 2 "
                "r_max) %.4g on average, %.0f%% of the box's cells of that side empty\n",
                f.summary.box_nu, boundary_description(s).c_str(), f.summary.window, f.summary.mean_nu,
                100 * f.summary.empty_fraction);
    std::printf("local nu:");
    for (std::size_t b = 0; b < f.summary.histogram.size(); ++b)
      if (f.summary.histogram[b] >= 0.005)
        std::printf(" [%.2f,%.2f) %.0f%%", b * FieldSummary::kHistogramBin, (b + 1) * FieldSummary::kHistogramBin,
                    100 * f.summary.histogram[b]);
    std::printf("\n");
    if (f.far_from_homogeneous())
      std::printf("far from homogeneous: the box's nu would mislead; the sizes follow the field model "
                  "(docs/MODEL.md section 14; --homogeneous for the box's nu)\n");
    else
      std::printf("close to homogeneous: the sizes are the paper's model's at the box's nu; the predictions "
                  "the field model's (docs/MODEL.md section 14)\n");
  } else if (in.nu_from_box)
    std::printf("nu = %g from the file's box (boundary %s)\n", in.nu, boundary_description(s).c_str());
  else
    std::printf("nu = %g (given)\n", in.nu);
  if (r.tilt_inflation > 1)
    std::printf("tilted box: its grid searches the mapped packing, radii and cell sizes x c = %.4g, random centres at "
                "c^%d nu = %.4g; the sizes and predictions are its (docs/MODEL.md section 12)\n",
                r.tilt_inflation, in.d, in.nu * std::pow(r.tilt_inflation, in.d));
  std::printf("K = %g (%s)\n\n", k.K, k_text(k).c_str());
  std::printf("%s HGrid, %d level%s; cell sizes in the file's unit (level h holds diameters in (s_h-1, s_h]):\n",
              search == Search::top_down ? "Top-Down" : "Bottom-Up", r.levels(), r.levels() == 1 ? "" : "s");
  std::printf("%7s %14s %12s %12s\n", "level", "cell size", "particles", "per cell");
  for (int h = 0; h < r.levels(); ++h)
    std::printf("%7d %14.6g %11.4g%% %12.4g\n", h + 1, r.sizes[h], 100 * r.model.P[h], r.model.m[h]);
  std::printf("predicted T/N = %.4g (overlap tests %.4g + K x cell accesses %.4g, per particle)\n", r.model.T_over_N,
              r.model.T_cd_over_N, r.model.T_ca_over_N);
  std::printf("linked cell (one level of size 2 r_max = %g): T/N = %.4g; predicted speed-up %.4gx\n",
              r.linked_cell_size, r.linked_cell.T_over_N, r.speedup());
  if (r.field && r.field->sizes_from_field())
    std::printf("predictions from the field model (effective nu %.4g); the homogeneous model at the box's nu predicts "
                "T/N = %.4g for these sizes, and would have chosen %zu level%s (field model T/N %.4g)\n",
                r.field->nu_effective, r.field->homogeneous_T_over_N, r.field->homogeneous_sizes.size(),
                r.field->homogeneous_sizes.size() == 1 ? "" : "s", r.field->homogeneous_sizes_T_over_N);
  else if (r.field)
    std::printf("predictions from the field model (effective nu %.4g); the homogeneous model at the box's nu: T/N = "
                "%.4g\n",
                r.field->nu_effective, r.field->homogeneous_T_over_N);
  if (r.seconds)
    std::printf("sizes minimise this machine's predicted seconds (time model): build + query %.4g s, linked cell "
                "%.4g s, speed-up %.4gx\n",
                r.seconds->total(), r.linked_cell_seconds->total(), r.speedup_seconds());
  else
    std::printf("sizes minimise T (no time model used: `hgrid calibrate` measures one, or give --cost time)\n");
  std::printf("\n");
  std::printf("LAMMPS (atom_style sphere, granular pair style; %zu collections from LAMMPS's own cost model, %s "
              "coefficients; bounds rounded up to %d digits):\n",
              r.lammps_collections.size(), r.lammps_model_source.c_str(), kPasteDigits);
  for (const auto& line : lammps_settings(r.lammps_collections, o.skin)) std::printf("  %s\n", line.c_str());
  std::printf("\nMercuryDPM:\n");
  for (const auto& line : mercurydpm_settings(r.sizes, search)) std::printf("  %s\n", line.c_str());
}

void print_json(const RecommendOptions& o, const ParticleSet& s, const FileInputs& in, const KChoice& k,
                const Recommendation& r, Search search, std::size_t first, std::size_t last) {
  nlohmann::json j = nlohmann::json::parse(recommendation_json(r, k, search, o.skin));
  j["file"] = o.file;
  j["format"] = to_string(s.format);
  j["frames"] = {first, last};
  j["n"] = s.size();
  j["d"] = in.d;
  j["nu"] = r.field ? r.field->nu_effective : in.nu;
  j["nu_source"] = r.field ? "field" : in.nu_from_box ? "box" : "given";
  j["box"] = s.box ? nlohmann::json(std::vector<double>(s.box->begin(), s.box->begin() + in.d)) : nlohmann::json();
  j["tilt"] = s.tilted() ? nlohmann::json(tilt_values(s.tilt, in.d))
                     : nlohmann::json();
  j["boundary"] = boundary_description(s);
  std::cout << j.dump(2) << "\n";
}

void run_recommend(const RecommendOptions& o) {
  if (!(std::isfinite(o.skin) && o.skin >= 0)) throw InputError("skin", "must be a finite number >= 0");
  const Search search = parse_search(o.search);
  std::optional<std::pair<std::int64_t, std::int64_t>> range;
  if (!o.frames.empty()) {
    if (o.frame) throw InputError("frames", "give --frame or --frames, not both");
    if (o.nu || o.homogeneous) throw InputError("frames", "uses the particles' density field: not with --nu or --homogeneous");
    const auto colon = o.frames.find(':');
    std::int64_t a = 0, b = 0;
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no colon");
      std::size_t used_a = 0, used_b = 0;
      a = std::stoll(o.frames.substr(0, colon), &used_a);
      b = std::stoll(o.frames.substr(colon + 1), &used_b);
      if (used_a != colon || used_b != o.frames.size() - colon - 1) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
      throw InputError("frames", "must be FIRST:LAST, two snapshot numbers (0, 1, ... or -1, -2, ... from the end); got '" +
                                     o.frames + "'");
    }
    range.emplace(a, b);
  }
  // --boundary: for a file that does not say its boundary (a MercuryDPM
  // .data file, a table without `# boundary`); one that says another is refused.
  const std::optional<Boundary> given_boundary =
      o.boundary.empty() ? std::nullopt : std::optional<Boundary>(parse_boundary(o.boundary, "boundary"));
  const auto with_boundary = [&](ParticleSet p) {
    if (!given_boundary) return p;
    if (p.mixed_boundary || (p.boundary && *p.boundary != *given_boundary))
      throw InputError("boundary", o.file + " says its boundary (" + boundary_description(p) +
                                       "); --boundary is for files that do not");
    p.boundary = given_boundary;
    return p;
  };
  ParticleSet s = with_boundary(
      read_particles(o.file, Isolation::child_process, range ? std::optional<std::int64_t>(range->first) : o.frame));
  std::optional<DensityField> field = o.nu || o.homogeneous ? std::nullopt : density_field_of(s);
  std::size_t first = s.frame, last = s.frame;
  if (range) {
    const auto absolute = [&](std::int64_t k) { return k < 0 ? std::int64_t(s.frames) + k : k; };
    const std::int64_t a = absolute(range->first), b = absolute(range->second);
    if (!(0 <= a && a <= b && b < std::int64_t(s.frames)))
      throw InputError("frames", "must run forward within the file's " + std::to_string(s.frames) +
                                     " snapshots (0.." + std::to_string(s.frames - 1) + ", or -" + std::to_string(s.frames) +
                                     "..-1 from the end); got '" + o.frames + "'");
    if (!field) throw InputError("frames", o.file + " has no positions in an untilted box: no density field to average");
    first = std::size_t(a), last = std::size_t(b);
    for (std::int64_t k = a + 1; k <= b; ++k) {
      s = with_boundary(read_particles(o.file, Isolation::child_process, k));
      const std::optional<DensityField> more = density_field_of(s);
      if (!more || more->d() != field->d())
        throw InputError("frames", "snapshot " + std::to_string(k) + " of " + o.file + " has no positions or another dimension");
      field->add_frame(s.positions, s.radii, FieldBox{s.d, *s.box, s.periodic_per_axis()});
    }
    s.radii = field->radii();  // the sizes hold every snapshot's particles
  }
  const FileInputs in = file_inputs(s, o.file, o.d, o.nu);
  const KChoice k = choose_K(o.K);
  // The time model: asked for, or by default when the calibration that gave
  // K has one for this dimension.
  const std::optional<TimeModelUse> time = choose_time_model(o.cost, k, in.d, double(s.size()));
  // Positions known and no --nu: the model over the particles' own density
  // field (docs/MODEL.md section 14).
  // A tilted box: the model of the mapped packing its grid searches (section 12).
  Recommendation r = field ? recommend_for_field(*field, ModelParams{in.d, in.nu, k.K, search}, time)
                           : recommend_tilted(s.radii, ModelParams{in.d, in.nu, k.K, search}, tilt_inflation(s), time);
  add_lammps_collections(r, s.radii, in.d, r.field ? r.field->nu_effective : in.nu);
  if (o.json) print_json(o, s, in, k, r, search, first, last);
  else print_text(o, s, in, k, r, search, first, last);
}

}  // namespace

void register_recommend_commands(CLI::App& app) {
  auto o = std::make_shared<RecommendOptions>();
  auto* sub = app.add_subcommand("recommend", "cell sizes for your own particles, and settings for LAMMPS and MercuryDPM");
  sub->add_option("FILE", o->file,
                  "particle file (HDF5, CSV/text, LAMMPS data or dump, MercuryDPM .data or .restart; docs/PARTICLE_FILES.md)")
      ->required();
  add_frame_option(sub, o->frame);
  sub->add_option("--frames", o->frames,
                  "FIRST:LAST: choose the sizes for a run over these snapshots of a dump (0, 1, ... or -1, -2, ... "
                  "from the end; sizes are set once per run): the field model's cost per particle over all of them");
  sub->add_option("--nu", o->nu,
                  "packing fraction of a homogeneous packing (default: the particles' own density field when the file "
                  "has positions and an untilted box, else the box's; needed when it has none)");
  sub->add_option("--boundary", o->boundary,
                  "walls|periodic: the boundary of a file that does not say its own (a MercuryDPM .data file, a "
                  "table without '# boundary'; else periodic is assumed); a file that says another is refused");
  sub->add_flag("--homogeneous", o->homogeneous, "take nu from the box even when the file has positions (the paper's model)");
  sub->add_option("--d", o->d, "dimension, 2 or 3 (default: from the file)");
  sub->add_option("--K", o->K, std::string(kKHelp) + " (default: the stored calibration if any, else 0.2)");
  sub->add_option("--search", o->search, "topdown | bottomup")->capture_default_str();
  sub->add_option("--cost", o->cost,
                  "what the sizes minimise: count (T = tests + K accesses), time (this machine's predicted seconds, "
                  "from `hgrid calibrate`), or auto (time when the calibration used for K has a time model)")
      ->capture_default_str();
  sub->add_option("--skin", o->skin, "LAMMPS neighbor skin to print (the file's unit)")->capture_default_str();
  sub->add_flag("--json", o->json, "print JSON (keys below)");
  sub->footer(kJsonKeys);
  sub->callback([o] { run_recommend(*o); });
}

}  // namespace hgrid::cli
