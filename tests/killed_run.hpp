// A generation killed part-way, for the resumption tests.
#pragma once
#include <cstddef>
#include <vector>

#include "hgridlab/packing/generate.hpp"

namespace hgrid::test {

/// Generates s with a checkpoint after every sweep and kills the run after
/// the `kill_after`-th; returns the checkpoints it saved (the last one is
/// where a resumption starts).
inline std::vector<Packing> checkpoints_until_killed(PackingSpec s, std::size_t kill_after) {
  s.checkpoint_seconds = 0;
  std::vector<Packing> checkpoints;
  struct Killed {};
  try {
    generate_packing(s, nullptr, [&](const Packing& c) {
      checkpoints.push_back(c);
      if (checkpoints.size() == kill_after) throw Killed{};
    });
  } catch (const Killed&) {
  }
  return checkpoints;
}

}  // namespace hgrid::test
