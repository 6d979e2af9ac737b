// The Python module `hgridlab` (pybind11): cell sizes for a list of radii,
// the overlapping pairs and the counted work of an HGrid search, and the
// particle file readers. numpy arrays in and out; an InputError becomes a
// ValueError with the same one-line message. Uses the library's public
// headers only.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "hgridlab/calibration/k_choice.hpp"
#include "hgridlab/advice/recommend.hpp"
#include "hgridlab/advice/recommend_json.hpp"
#include "hgridlab/advice/skin_model.hpp"
#include "hgridlab/advice/skin_tuner.hpp"
#include "hgridlab/model/distribution.hpp"
#include "hgridlab/measure/fields.hpp"
#include "hgridlab/measure/measurement.hpp"
#include "hgridlab/measure/pairs.hpp"
#include "hgridlab/base/error.hpp"
#include "hgridlab/contacts/contact_list.hpp"
#include "hgridlab/grid/version.hpp"
#include "hgridlab/io/particle_file.hpp"
#include "hgridlab/packing/packing.hpp"
#include "hgridlab/packing/packing_sizes.hpp"

namespace py = pybind11;
using namespace hgrid;

namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::vector<double> to_vector(const DoubleArray& a, const char* field) {
  if (a.ndim() != 1) throw InputError(field, "must be a 1-D array");
  return std::vector<double>(a.data(), a.data() + a.size());
}

using Tilt = std::optional<std::vector<double>>;

/// A validated Packing from numpy arrays (positions N x d, radii N, box d;
/// tilt: a tilted periodic box's xy (2D) or xy, xz, yz (3D), LAMMPS's).
Packing make_packing(const DoubleArray& positions, const DoubleArray& radii, const DoubleArray& box, bool periodic,
                     const Tilt& tilt = std::nullopt) {
  if (positions.ndim() != 2) throw InputError("positions", "must be an N x d array");
  Packing p;
  p.d = static_cast<int>(positions.shape(1));
  if (p.d != 2 && p.d != 3) throw InputError("positions", "must have 2 or 3 columns");
  p.radii = to_vector(radii, "radii");
  if (static_cast<std::size_t>(positions.shape(0)) != p.radii.size())
    throw InputError("radii", "must have one value per row of positions");
  const std::vector<double> b = to_vector(box, "box");
  if (b.size() != static_cast<std::size_t>(p.d)) throw InputError("box", "must have d side lengths");
  for (int a = 0; a < p.d; ++a) p.box[a] = b[a];
  p.boundary = periodic ? Boundary::periodic : Boundary::walls;
  p.positions.assign(positions.data(), positions.data() + positions.size());
  if (tilt) {
    if (tilt->size() != (p.d == 2 ? 1u : 3u)) throw InputError("tilt", p.d == 2 ? "must be [xy] in 2D" : "must be [xy, xz, yz] in 3D");
    for (std::size_t k = 0; k < tilt->size(); ++k) p.tilt[k] = (*tilt)[k];
  }
  validate(p);
  return p;
}

/// `sizes` when given, else the recommended sizes for the packing.
GridParams grid_params(const Packing& p, const std::optional<std::vector<double>>& sizes, const std::string& search) {
  const Search s = parse_search(search);
  if (sizes) return GridParams{*sizes, s};
  if (p.tilted()) return GridParams{model_sizes(p, SizeRequest{}, s, choose_K("").K), s};  // the mapped packing's
  return GridParams{recommend_for_packing(p, choose_K("").K, s).sizes, s};  // its density field's, as recommend()
}

py::dict recommend(const DoubleArray& radii, std::optional<double> nu, int d, const std::optional<py::object>& K,
                   const std::string& search, const std::string& cost, const std::optional<DoubleArray>& positions,
                   const std::optional<DoubleArray>& box, const std::optional<py::object>& periodic,
                   const std::optional<std::vector<double>>& tilt) {
  std::string k_text;
  if (K && !K->is_none()) k_text = py::isinstance<py::str>(*K) ? K->cast<std::string>() : format_number(K->cast<double>());
  const KChoice k = choose_K(k_text);
  const Search s = parse_search(search);
  const std::vector<double> r_list = to_vector(radii, "radii");
  if (positions.has_value() != box.has_value() && !(tilt && box))
    throw InputError(positions ? "box" : "positions", "positions and box go together (the density field needs both)");
  if (!positions && !nu && !tilt)
    throw InputError("nu", "give nu (a homogeneous packing), or positions and box (its density field)");
  const std::optional<TimeModelUse> time = choose_time_model(cost, k, d, static_cast<double>(r_list.size()));
  Recommendation r;
  if (tilt) {  // a tilted box: the mapped packing its grid searches (no density field)
    if (!box) throw InputError("box", "a tilt needs the box's side lengths");
    const std::vector<double> b = to_vector(*box, "box");
    if (b.size() != static_cast<std::size_t>(d)) throw InputError("box", "must hold d = " + std::to_string(d) + " side lengths");
    if (tilt->size() != (d == 2 ? 1u : 3u)) throw InputError("tilt", d == 2 ? "must be [xy] in 2D" : "must be [xy, xz, yz] in 3D");
    double volume = 1, balls = 0;
    for (double v : b) volume *= v;
    for (double v : r_list) balls += ball_volume(d, v);
    if (!nu) nu = balls / volume;
    std::array<double, 3> t{};
    for (std::size_t k = 0; k < tilt->size(); ++k) t[k] = (*tilt)[k];
    r = recommend_tilted(r_list, ModelParams{d, *nu, k.K, s}, tilt_inflation(d, b, t), time);
  } else if (positions && !nu) {
    if (positions->ndim() != 2 || positions->shape(1) != d)
      throw InputError("positions", "must be an N x d array (d = " + std::to_string(d) + ")");
    if (static_cast<std::size_t>(positions->shape(0)) != r_list.size())
      throw InputError("radii", "must have one value per row of positions");
    const std::vector<double> x(positions->data(), positions->data() + positions->size()), b = to_vector(*box, "box");
    if (b.size() != static_cast<std::size_t>(d)) throw InputError("box", "must hold d = " + std::to_string(d) + " side lengths");
    FieldBox fb{d, {}, {true, true, true}};
    for (int a = 0; a < d; ++a) fb.side[a] = b[a];
    if (periodic && !periodic->is_none()) {
      if (py::isinstance<py::bool_>(*periodic)) fb.periodic.fill(periodic->cast<bool>());
      else {
        const auto per = periodic->cast<std::vector<bool>>();
        if (per.size() != static_cast<std::size_t>(d)) throw InputError("periodic", "must be a bool or d bools");
        for (int a = 0; a < d; ++a) fb.periodic[a] = per[a];
      }
    }
    std::optional<DensityField> field;
    {
      py::gil_scoped_release release;
      field.emplace(x, r_list, fb);
      r = recommend_for_field(*field, ModelParams{d, std::min(1.0, field->box_nu()), k.K, s}, time);
    }
  } else {
    r = recommend_cell_sizes(r_list, ModelParams{d, *nu, k.K, s}, time);
  }
  const double nu_used = r.field ? r.field->nu_effective : *nu;
  add_lammps_collections(r, r_list, d, nu_used);
  py::dict out = py::module_::import("json").attr("loads")(recommendation_json(r, k, s, 0.0));
  out["d"] = d;
  out["nu"] = nu_used;
  return out;
}

py::array_t<std::uint32_t> pairs(const DoubleArray& positions, const DoubleArray& radii, const DoubleArray& box,
                                 bool periodic, const std::optional<std::vector<double>>& sizes,
                                 const std::string& search, int threads, const Tilt& tilt) {
  const Packing p = make_packing(positions, radii, box, periodic, tilt);
  GridParams params = grid_params(p, sizes, search);
  params.threads = check_threads(threads);
  std::vector<std::vector<std::uint32_t>> per(static_cast<std::size_t>(resolve_threads(params.threads)));
  {
    py::gil_scoped_release release;
    for_each_packing_pair(p, params, [&](int t, std::uint32_t i, std::uint32_t j) {
      auto& v = per[static_cast<std::size_t>(t)];
      v.push_back(i), v.push_back(j);
    });
  }
  std::vector<std::uint32_t> flat;
  for (const auto& v : per) flat.insert(flat.end(), v.begin(), v.end());
  py::array_t<std::uint32_t> out({static_cast<py::ssize_t>(flat.size() / 2), py::ssize_t{2}});
  std::copy(flat.begin(), flat.end(), out.mutable_data());
  return out;
}

/// The measurement as a dict: every field of its table (measure/fields.hpp),
/// None where not measured.
py::dict to_dict(const Measurement& m) {
  py::dict out;
  for (const MeasurementField& f : measurement_fields())
    out[f.name] = std::visit(
        [](const auto& v) -> py::object {
          if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::monostate>)
            return py::none();
          else
            return py::cast(v);
        },
        f.value(m));
  return out;
}

py::dict count(const DoubleArray& positions, const DoubleArray& radii, const DoubleArray& box, bool periodic,
               const std::optional<std::vector<double>>& sizes, const std::string& search, double K, int threads,
               bool model, const Tilt& tilt, double excluded_budget) {
  if (!(excluded_budget >= 0)) throw InputError("excluded_budget", "must be >= 0 (0: no budget)");
  const Packing p = make_packing(positions, radii, box, periodic, tilt);
  GridParams params = grid_params(p, sizes, search);
  params.threads = check_threads(threads);
  MeasureOptions mo;
  mo.K = K;
  mo.predict(model ? Predictions::excluded : Predictions::none);
  mo.excluded_work_budget = excluded_budget;
  Measurement m;
  {
    py::gil_scoped_release release;
    m = measure(p, params, mo);
  }
  return to_dict(m);
}

py::dict read_particle_file(const std::string& path, std::optional<std::int64_t> frame) {
  ParticleSet s = read_particles(path, Isolation::child_process, frame);
  py::dict out;
  out["format"] = to_string(s.format);
  out["frame"] = s.frame;
  out["frames"] = s.frames;
  out["d"] = s.d;
  out["radii"] = py::array_t<double>(static_cast<py::ssize_t>(s.size()), s.radii.data());
  if (s.has_positions()) {
    py::array_t<double> pos({static_cast<py::ssize_t>(s.size()), static_cast<py::ssize_t>(s.d)});
    std::copy(s.positions.begin(), s.positions.end(), pos.mutable_data());
    out["positions"] = pos;
  } else {
    out["positions"] = py::none();
  }
  out["box"] = s.box ? py::cast(std::vector<double>(s.box->begin(), s.box->begin() + s.d)) : py::none();
  out["tilt"] = s.tilted() ? py::cast(tilt_values(s.tilt, s.d)) : py::none();
  out["boundary"] = s.mixed_boundary ? py::cast("mixed") : s.boundary ? py::cast(to_string(*s.boundary)) : py::none();
  out["nu"] = s.box && s.d > 0 ? py::cast(s.packing_fraction()) : py::none();
  return out;
}

/// hgridlab.ContactList: a contact list kept between the steps of a
/// simulation (contacts/contact_list.hpp). The dimension is the box's length.
class PyContactList {
 public:
  PyContactList(const DoubleArray& box, const std::vector<bool>& periodic, const std::optional<DoubleArray>& origin,
                const Tilt& tilt, const py::object& skin, double skin_rel, const py::object& sizes, const std::string& search,
                int threads) {
    const std::vector<double> b = to_vector(box, "box");
    d_ = static_cast<int>(b.size());
    if (d_ != 2 && d_ != 3) throw InputError("box", "must have 2 or 3 side lengths (the dimension)");
    ContactListParams p;
    if (py::isinstance<py::str>(sizes)) {
      if (sizes.cast<std::string>() != "auto") throw InputError("sizes", "must be a list of cell sizes, None or 'auto'");
      auto_sizes_ = true;
    } else if (!sizes.is_none()) {
      p.sizes = sizes.cast<std::vector<double>>();
    }
    p.search = parse_search(search);
    p.threads = check_threads(threads);
    if (py::isinstance<py::str>(skin)) {
      if (skin.cast<std::string>() != "auto") throw InputError("skin", "must be a number >= 0 or 'auto'");
      auto_skin_ = true;
    } else {
      p.skin = skin.cast<double>();
    }
    p.skin_rel = skin_rel;
    volume_ = 1;
    for (double side : b) volume_ *= side;
    tuner_ = SkinTuner(d_);
    if (d_ == 2) list_.emplace<ContactList<2>>(list_box<2>(b, periodic, origin, tilt, tilt.has_value()), p);
    else list_.emplace<ContactList<3>>(list_box<3>(b, periodic, origin, tilt, tilt.has_value()), p);
  }

  /// New positions (N x d) and radii (N, or None: the last ones); returns
  /// whether the list was rebuilt. C-contiguous float64 is read in place.
  bool update(const DoubleArray& positions, const std::optional<DoubleArray>& radii) {
    if (positions.ndim() != 2 || positions.shape(1) != d_)
      throw InputError("positions", "must be an N x " + std::to_string(d_) + " array");
    const auto n = static_cast<std::size_t>(positions.shape(0));
    std::span<const double> r;
    DoubleArray r_arr;
    if (radii) {
      r_arr = *radii;
      if (r_arr.ndim() != 1 || static_cast<std::size_t>(r_arr.shape(0)) != n)
        throw InputError("radii", "must be a 1-D array with one radius per row of positions");
      r = {r_arr.data(), n};
    } else {
      if (!radii_ || static_cast<std::size_t>(radii_->shape(0)) != n)
        throw InputError("radii", "needed at the first update and whenever the number of particles changes");
      r = {radii_->data(), n};
    }
    const std::span<const double> x(positions.data(), n * static_cast<std::size_t>(d_));
    bool rebuilt = false;
    {
      py::gil_scoped_release release;
      std::visit(
          [&](auto& l) {
            if (radii && (auto_sizes_ || auto_skin_)) first_choices(l, x, r);
            rebuilt = l.update(x, r);
            if (auto_skin_ && rebuilt) tune_skin(l, x, r);
          },
          list_);
    }
    if (radii) radii_ = r_arr;  // kept (a reference, no copy) once the update has passed
    return rebuilt;
  }

  void set_box(const DoubleArray& box, const std::optional<DoubleArray>& origin, const Tilt& tilt) {
    const std::vector<double> b = to_vector(box, "box");
    if (static_cast<int>(b.size()) != d_) throw InputError("box", "must have " + std::to_string(d_) + " side lengths");
    std::visit(
        [&](auto& l) {
          constexpr int D = std::decay_t<decltype(l)>::dimension;
          std::vector<bool> per(D);
          for (int k = 0; k < D; ++k) per[k] = l.box().periodic[k];
          const bool tri = l.box().triclinic;
          if (tilt && !tri) throw InputError("tilt", "the list was made without tilt= (an orthogonal box)");
          ListBox<D> nb = list_box<D>(b, per, origin ? origin : std::optional<DoubleArray>(origin_of(l.box())), tilt, tri);
          if (tri && !tilt) nb.tilt = l.box().tilt;  // None keeps the tilts
          l.set_box(nb);
        },
        list_);
  }

  /// The contacts (i, j), i < j, ascending, as an (M, 2) uint32 array.
  py::array_t<std::uint32_t> pairs() const {
    return std::visit(
        [&](const auto& l) {
          py::array_t<std::uint32_t> out({static_cast<py::ssize_t>(l.contacts()), py::ssize_t{2}});
          std::uint32_t* o = out.mutable_data();
          {
            py::gil_scoped_release release;
            l.for_each_contact([&](std::uint32_t i, std::uint32_t j) {
              *o++ = i;
              *o++ = j;
            });
          }
          return out;
        },
        list_);
  }

  /// The contacts as compressed rows: (start (N + 1), partners (M)).
  py::tuple neighbours() const {
    return std::visit(
        [&](const auto& l) {
          const auto st = l.start();
          const auto pa = l.partners();
          return py::make_tuple(py::array_t<std::uint32_t>(static_cast<py::ssize_t>(st.size()), st.data()),
                                py::array_t<std::uint32_t>(static_cast<py::ssize_t>(pa.size()), pa.data()));
        },
        list_);
  }

  py::dict stats() const {
    return std::visit(
        [&](const auto& l) {
          const ContactListStats& s = l.stats();
          py::dict out;
          out["steps"] = s.steps;
          out["builds"] = s.builds;
          out["candidates"] = s.candidates;
          out["contacts"] = s.contacts;
          out["seconds_check"] = s.seconds_check;
          out["seconds_build"] = s.seconds_build;
          out["seconds_grid"] = s.seconds_grid;
          out["seconds_test"] = s.seconds_test;
          out["seconds_per_step"] = s.seconds_per_step();
          out["grid_sizes"] = l.grid_sizes();
          out["skin"] = l.params().skin;
          const auto& predicted = tuner_.predicted();
          out["predicted_seconds_per_step"] = predicted ? py::cast(predicted->seconds_per_step) : py::none();
          out["predicted_steps_per_build"] = predicted ? py::cast(predicted->steps_per_build) : py::none();
          return out;
        },
        list_);
  }

  int d() const { return d_; }

 private:
  template <int D>
  static ListBox<D> list_box(const std::vector<double>& b, const std::vector<bool>& periodic,
                             const std::optional<DoubleArray>& origin, const Tilt& tilt, bool triclinic) {
    ListBox<D> lb;
    lb.triclinic = triclinic;
    if (tilt) {
      if (tilt->size() != (D == 2 ? 1u : 3u))
        throw InputError("tilt", D == 2 ? "must be [xy] in 2D" : "must be [xy, xz, yz] in 3D");
      for (std::size_t k = 0; k < tilt->size(); ++k) lb.tilt[k] = (*tilt)[k];
    }
    if (periodic.size() != static_cast<std::size_t>(D))
      throw InputError("periodic", "must have one flag per axis (" + std::to_string(D) + ")");
    for (int k = 0; k < D; ++k) {
      lb.side[k] = b[k];
      lb.periodic[k] = periodic[k];
    }
    if (origin) {
      const std::vector<double> o = to_vector(*origin, "origin");
      if (o.size() != static_cast<std::size_t>(D)) throw InputError("origin", "must have one value per axis");
      for (int k = 0; k < D; ++k) lb.origin[k] = o[k];
    }
    return lb;
  }
  template <int D>
  static DoubleArray origin_of(const ListBox<D>& b) {
    DoubleArray o(D);
    for (int k = 0; k < D; ++k) o.mutable_data()[k] = b.origin[k];
    return o;
  }

  /// The radii's packing fraction in the box.
  double packing_fraction(std::span<const double> r) const {
    double v = 0;
    for (double x : r) v += ball_volume(d_, x);
    return v / volume_;
  }

  /// The density field of positions x (N x d) and radii r in the list's
  /// (untilted) box.
  template <class L>
  DensityField field_of(const L& l, std::span<const double> x, std::span<const double> r) const {
    const auto& box = l.box();
    FieldBox fb{d_, {}, {}};
    std::vector<double> rel(x.begin(), x.end());
    for (int a = 0; a < d_; ++a) {
      fb.side[a] = box.side[a], fb.periodic[a] = box.periodic[a];
      for (std::size_t i = 0; i < r.size(); ++i) rel[i * d_ + a] -= box.origin[a];
    }
    return DensityField(rel, std::vector<double>(r.begin(), r.end()), fb);
  }

  /// The packing fraction that shapes the skin model's shell of candidates:
  /// the particles' mean local nu (their density field, windows of the
  /// linked cell's scan) in an untilted box, else the box's.
  template <class L>
  double skin_nu(const L& l, std::span<const double> x, std::span<const double> r) const {
    if (l.box().triclinic || r.empty()) return std::min(packing_fraction(r), 0.95);
    const double rmax = *std::max_element(r.begin(), r.end());
    return std::min(field_of(l, x, r).summary(6 * rmax).mean_nu, 0.95);
  }

  /// sizes="auto": the sizes `hgrid recommend` gives the first positions and
  /// radii (their density field in an untilted box, else their packing
  /// fraction; K as `hgrid recommend`); skin="auto": the tuner's first skin
  /// (a tenth of the mean diameter), tuned from the builds on.
  template <class L>
  void first_choices(L& l, std::span<const double> x, std::span<const double> r) {
    if (r.empty()) return;
    const double nu = std::min(packing_fraction(r), 0.99);
    if (auto_sizes_ && !sized_once_) {  // once: new sizes would mean a new grid
      sized_once_ = true;
      const std::vector<double> radii(r.begin(), r.end());
      const ModelParams mp{d_, nu, choose_K("").K, Search::top_down};
      if (!l.box().triclinic) l.set_sizes(recommend_for_field(field_of(l, x, r), mp).sizes);
      else  // the mapped packing its tilted grid searches, at the box's tilt now
        l.set_sizes(recommend_tilted(radii, mp, tilt_inflation(d_, l.box().side, l.box().tilt)).sizes);
    }
    if (auto_skin_ && !tuned_once_) {
      l.set_skin(SkinTuner::first_skin(r), l.params().skin_rel);
      tuned_once_ = true;
    }
  }

  /// skin="auto": every SkinTuner::kBuildsPerWindow builds, the skin model
  /// (advice/skin_tuner.hpp) from what the list measured over them picks the
  /// next skin.
  template <class L>
  void tune_skin(L& l, std::span<const double> x, std::span<const double> r) {
    const ContactListStats& s = l.stats();
    if (!tuner_.due(s)) return;  // the field only when the tuner will use it
    if (const auto next = tuner_.after_build(s, l.params().skin, r, skin_nu(l, x, r)))
      l.set_skin(*next, l.params().skin_rel);
  }

  int d_ = 3;
  double volume_ = 1;
  bool auto_sizes_ = false, auto_skin_ = false, tuned_once_ = false, sized_once_ = false;
  SkinTuner tuner_{3};
  std::variant<ContactList<2>, ContactList<3>> list_{std::in_place_type<ContactList<3>>, ListBox<3>{{1, 1, 1}, {}, {}},
                                                     ContactListParams{}};
  std::optional<DoubleArray> radii_;
};

}  // namespace

PYBIND11_MODULE(hgridlab, m) {
  m.doc() = "hgridlab: hierarchical-grid (HGrid) contact detection and its cost model "
            "(Krijgsman, Ogarko & Luding, Comp. Part. Mech. 1 (2014))";
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  m.def("recommend", &recommend, py::arg("radii"), py::arg("nu") = py::none(), py::arg("d") = 3, py::arg("K") = py::none(),
        py::arg("search") = "topdown", py::arg("cost") = "auto", py::arg("positions") = py::none(),
        py::arg("box") = py::none(), py::arg("periodic") = py::none(), py::arg("tilt") = py::none(),
        "Optimal cell sizes for these radii (any unit) at packing fraction nu: a dict with the keys of "
        "`hgrid recommend --json` that do not describe a file (levels, sizes in the radii's unit, T_over_N, speedup "
        "over the linked cell, K and K_source, lammps and mercurydpm lines, ...) plus d and nu. K: a number, 'auto', "
        "or None for the stored calibration if any, else 0.2. cost: 'count' (the paper's T), 'time' (this "
        "machine's time model, from `hgrid calibrate`) or 'auto' (the time model when K came from a calibration "
        "that has one), as `hgrid recommend --cost`. tilt ([xy] or [xy, xz, yz], with box): a sheared "
        "(triclinic) box, whose grid searches the mapped packing (docs/MODEL.md section 12); nu defaults to the "
        "box's.");
  m.def("pairs", &pairs, py::arg("positions"), py::arg("radii"), py::arg("box"), py::arg("periodic") = true,
        py::arg("sizes") = py::none(), py::arg("search") = "topdown", py::arg("threads") = 0, py::arg("tilt") = py::none(),
        "Every overlapping pair (i, j), i < j, as an (M, 2) uint32 array, in no particular order; sizes: cell sizes "
        "(default: recommended); threads: 0 = all cores (OMP_NUM_THREADS), the same pairs for any number; tilt: a "
        "tilted periodic box's [xy] (2D) or [xy, xz, yz] (3D), LAMMPS's triclinic box (a Lees-Edwards offset is xy).");
  m.def("count", &count, py::arg("positions"), py::arg("radii"), py::arg("box"), py::arg("periodic") = true,
        py::arg("sizes") = py::none(), py::arg("search") = "topdown", py::arg("K") = kPaperK, py::arg("threads") = 0,
        py::arg("model") = false, py::arg("tilt") = py::none(), py::arg("excluded_budget") = kDiscWorkPerSecond,
        "The counted search (the same counts for any number of threads) as a dict with the fields of "
        "`hgrid count --json` (docs/MEASUREMENT.md): cell_accesses, narrow_phase_checks, contacts, "
        "particles_per_level, accesses_by_level and checks_by_level (L x L, row-major: level of the particle, level "
        "searched), sizes (as used), T_over_N, ...; model=True adds the cost models' predictions (model_*), for "
        "discs the excluded-volume model within excluded_budget multiply-adds (as `hgrid count --excluded-budget`; "
        "0: none).");
  m.def("measurement_fields", [] {
    py::list out;
    for (const MeasurementField& f : measurement_fields())
      out.append(py::make_tuple(f.name, f.unit, f.meaning));
    return out;
  }, "The fields of a measurement (count's dict): (name, unit, meaning) tuples.");
  m.def("read_packing", &read_particle_file, py::arg("path"), py::arg("frame") = py::none(),
        "A particle file of any supported format: radii, positions (or None), box (or None), tilt (or None), "
        "boundary (or None), d, format, nu (or None).");
  py::class_<PyContactList>(m, "ContactList",
                            "Contacts step after step: keeps the candidate pairs within r_i + r_j + skin (each radius "
                            "also inflated by skin_rel r_i) and, at every update, hands over exactly the pairs with "
                            "distance < r_i + r_j (minimum image on periodic axes), the same set as a fresh grid; "
                            "rebuilt with the HGrid only when a particle may have moved or grown through its skin, "
                            "or the box changed beyond it. box: the sides (its length is the dimension, 2 or 3); "
                            "periodic: a flag per axis; origin: the lower corner (default 0); tilt: a triclinic box's "
                            "[xy] (2D) or [xy, xz, yz] (3D), LAMMPS's (every axis periodic; its tilts may then "
                            "change at every set_box); skin: the pair skin, or "
                            "'auto' (the skin model re-chooses it from what the list measures, every few builds); "
                            "sizes: cell sizes for the radii, None (doubling from the smallest to the largest "
                            "diameter) or 'auto' (the cost model's, as recommend); threads: 0 = all cores, the same "
                            "pairs for any number.")
      .def(py::init<const DoubleArray&, const std::vector<bool>&, const std::optional<DoubleArray>&, const Tilt&,
                    const py::object&, double, const py::object&, const std::string&, int>(),
           py::arg("box"), py::arg("periodic") = std::vector<bool>{true, true, true}, py::arg("origin") = py::none(),
           py::arg("tilt") = py::none(),
           py::arg("skin") = py::float_(0.0), py::arg("skin_rel") = 0.0, py::arg("sizes") = py::none(),
           py::arg("search") = "bottomup", py::arg("threads") = 1)
      .def("update", &PyContactList::update, py::arg("positions"), py::arg("radii") = py::none(),
           "New positions (N x d) and radii (N; None: the last ones). Returns whether the candidates were rebuilt. "
           "Bad input raises ValueError naming the field (a particle outside a walled axis names the particle and "
           "the axis) and leaves the list as it was.")
      .def("pairs", &PyContactList::pairs, "The contacts (i, j), i < j, ascending, as an (M, 2) uint32 array.")
      .def("neighbours", &PyContactList::neighbours,
           "The contacts as compressed rows (start, partners): the partners j > i of particle i are "
           "partners[start[i]:start[i + 1]], ascending.")
      .def("set_box", &PyContactList::set_box, py::arg("box"), py::arg("origin") = py::none(),
           py::arg("tilt") = py::none(),
           "A new box (sides; origin and tilt: None keeps them); the axes' boundaries stay. A growing "
           "Lees-Edwards offset is a new tilt [xy] at every step (the offset less a multiple of lx).")
      .def_property_readonly("stats", &PyContactList::stats,
                             "steps, builds, candidates, contacts, seconds (check, build, test, per step), grid_sizes.")
      .def_property_readonly("d", &PyContactList::d);
  m.attr("__version__") = HGRIDLAB_VERSION;
}
