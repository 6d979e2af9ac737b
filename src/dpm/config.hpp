// What a DPM run simulates: box, boundary, contact law, time step and the
// physical effects a scene switches on. Validated before anything runs.
#pragma once
#include <array>
#include <vector>

#include "hgridlab/grid/geometry.hpp"
#include "hgridlab/grid/params.hpp"

namespace hgrid::dpm {

/// dt must resolve a contact with at least this many steps (dt <= t_c / 10);
/// Luding's DEM notes recommend about 50 for accuracy, 10 is the stability floor.
inline constexpr double kMinStepsPerContact = 10.0;

/// The tangential force of a frictional contact, capped by Coulomb's mu f_n:
/// viscous (gamma_t times the contact point's tangential velocity; no
/// memory), or a spring (Cundall & Strack 1979, as in Luding, "Cohesive,
/// frictional powders", Granular Matter 10 (2008), Sect. 2.2): the
/// tangential displacement xi, kept per contact from step to step (rotated
/// into the tangent plane, grown by v_t dt), f_t = k_t xi + gamma_t v_t; when
/// |f_t| exceeds mu f_n the contact slides and xi is set back to the length
/// the Coulomb force gives. Wall contacts stay viscous.
enum class TangentialLaw { viscous, spring };

inline const char* to_string(TangentialLaw t) { return t == TangentialLaw::viscous ? "viscous" : "spring"; }

struct DpmConfig {
  int d = 2;
  Boundary boundary = Boundary::walls;
  std::array<double, 3> box{};  // first d entries used; walls at 0 and box[k]
  // Linear spring-dashpot normal contact: every pair (and particle-wall
  // contact) lasts t_c and has normal restitution e (stiffness and damping
  // scale with the reduced mass; Luding, "Introduction to DEM", Sect. 2).
  double contact_time = 1.0;  // t_c
  double restitution = 0.8;   // e in (0, 1]
  double dt = 0.02;           // time step, <= t_c / kMinStepsPerContact
  // Optional effects (compiled in only when switched on).
  bool friction = false;
  double mu = 0.5;                // Coulomb coefficient
  double friction_damping = 1.0;  // tangential viscosity gamma_t = friction_damping * m_red / t_c
  TangentialLaw tangential = TangentialLaw::viscous;
  /// k_t / k_n of the spring law. 2/7 (3D; 1/3 in 2D) gives the tangential
  /// oscillation of a sticking contact the normal one's period.
  double tangential_stiffness = 2.0 / 7.0;
  bool gravity = false;
  std::array<double, 3> g{};
  double density = 1.0;  // mass = density * volume (disk area in 2D)
  // Contact detection.
  std::vector<double> sizes;  // HGrid cell sizes
  Search search = Search::top_down;
  /// Threads of the contact detection (0 = all cores, base/threads.hpp): the
  /// pairs are put in canonical order before the forces are summed, so the
  /// trajectory is the same, bit for bit, for any number.
  int threads = 1;
  /// The contact list's pair skin (contacts/contact_list.hpp), in the
  /// radii's units: candidates within r_i + r_j + skin, rebuilt when a
  /// particle may have moved through it. 0: rebuilt every step. The
  /// trajectory is the same, bit for bit, for any skin.
  double skin = 0;
};

/// Throws InputError naming the field (the scene key) and the allowed range.
void validate(const DpmConfig& c);

}  // namespace hgrid::dpm
