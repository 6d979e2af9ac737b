// A DPM simulation behind one runtime interface; the composition of effects
// (dimension, boundary, friction, gravity) is a compile-time choice made once
// by make_simulation, so the time loop has no branch on a switched-off effect.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "hgridlab/contacts/contact_list.hpp"
#include "hgridlab/dpm/config.hpp"
#include "hgridlab/packing/packing.hpp"

namespace hgrid::dpm {

/// Work and time of the steps taken so far. Effect counters stay 0 for
/// effects that are not compiled into the run.
struct StepStats {
  std::uint64_t steps = 0;
  std::uint64_t pair_contacts = 0;         // pair contacts handed to the force loop
  std::uint64_t wall_contacts = 0;
  std::uint64_t friction_evaluations = 0;  // tangential forces computed
  std::uint64_t gravity_evaluations = 0;   // particles given gravity
  std::uint64_t list_builds = 0;           // contact list rebuilds (every step with skin 0)
  ContactListStats list;                   // the contact list's own counts and seconds
  double seconds_contact_detection = 0;    // the contact list: builds + checks + tests
  double seconds_grid_build = 0;           //   of which: building the HGrid
  double seconds_query = 0;                //   of which: the rest (the search, storing the list, the skin
                                           //   check, the test of the candidates)
  double seconds_forces = 0;               // contact and wall forces
  double seconds_integration = 0;          // velocity-Verlet updates
};

class Simulation {
 public:
  virtual ~Simulation() = default;
  /// Advances n steps of size dt.
  virtual void run(std::uint64_t n) = 0;
  virtual double time() const = 0;
  /// Translational + rotational kinetic energy.
  virtual double kinetic_energy() const = 0;
  /// Elastic energy of the current overlaps (pairs and walls).
  virtual double elastic_energy() const = 0;
  virtual std::array<double, 3> momentum() const = 0;
  /// Positions and velocities, row-major N x d.
  virtual std::vector<double> positions() const = 0;
  virtual std::vector<double> velocities() const = 0;
  virtual const StepStats& stats() const = 0;
};

/// Builds the simulation for the composition the config asks for. `initial`
/// gives radii and centres (box and boundary must match the config),
/// `velocities` N x d (empty: at rest). Throws InputError for bad input.
std::unique_ptr<Simulation> make_simulation(const DpmConfig& c, const Packing& initial,
                                            const std::vector<double>& velocities);

}  // namespace hgrid::dpm
