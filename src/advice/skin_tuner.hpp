// skin = "auto" for a contact list (docs/CONTACT_LIST.md, "The skin model"):
// the skin model (advice/skin_model.hpp) applied as the run goes. The first
// skin is a tenth of the mean diameter; after every `builds_per_window`
// builds, what the list measured over them (its stats' differences) is set
// beside the last window measured at a skin at least kSkinRatio away, and
// the model's choice from the two is the skin of the next window (the first
// window's skin is doubled for the second, so that there are two). The measurements follow
// the run, so the choice follows it: a cooling gas slows and the skin
// grows, a pour speeds up and it shrinks.
//
//   ContactList<3> list(box, {sizes, Search::bottom_up, 1, SkinTuner::first_skin(r)});
//   SkinTuner tuner(3);
//   for (...) {
//     if (list.update(x, r))
//       if (auto s = tuner.after_build(list.stats(), list.params().skin, r, nu)) list.set_skin(*s);
//   }
#pragma once
#include <cstdint>
#include <optional>
#include <span>

#include "hgridlab/advice/skin_model.hpp"
#include "hgridlab/contacts/contact_list.hpp"

namespace hgrid {

/// What a contact list measured at one skin over a window of its run, from
/// its stats at the window's end (`now`) and start (`before`; a
/// default-constructed one for the whole run): steps per build, travel per step, candidates
/// tested per step and particle, seconds per build (grid; search and
/// storing) and per step (test; check), contacts per particle at the end.
/// n: the particles' number (> 0).
SkinMeasurement skin_measurement(double skin, const ContactListStats& now, const ContactListStats& before, double n);

/// Chooses a contact list's skin as the run goes (skin = "auto"; see above).
class SkinTuner {
 public:
  /// For a list in d (2 or 3) dimensions, re-chosen every builds_per_window
  /// (>= 1) builds. InputError naming the field otherwise.
  explicit SkinTuner(int d, std::uint64_t builds_per_window = kBuildsPerWindow);

  /// The first skin: a tenth of the mean diameter of `radii` (0 if empty).
  static double first_skin(std::span<const double> radii);

  /// After an update that rebuilt the list: the skin for the next window,
  /// or nothing (keep the skin). `s` the list's stats (cumulative, as
  /// ContactList::stats() gives them), `skin` its skin over the window,
  /// `radii` the particles' now, `nu` the packing fraction that shapes the
  /// shell of candidates (the particles' mean local nu where the box is not
  /// homogeneous: DensityField::summary; else the box's), in [0, 1).
  std::optional<double> after_build(const ContactListStats& s, double skin, std::span<const double> radii, double nu);

  /// Whether a window has ended by these stats (after_build would measure it).
  bool due(const ContactListStats& s) const { return s.builds >= last_.builds + window_; }

  /// The model's prediction at the last choice (nothing before the first).
  const std::optional<SkinPrediction>& predicted() const { return predicted_; }

  static constexpr std::uint64_t kBuildsPerWindow = 5;
  /// The two windows the model is given are at skins at least this far apart.
  static constexpr double kSkinRatio = 1.5;

 private:
  int d_;
  std::uint64_t window_;
  ContactListStats last_;                 // the stats when the window began
  std::optional<SkinMeasurement> other_;  // the last window measured at another skin
  std::optional<SkinPrediction> predicted_;
};

}  // namespace hgrid
