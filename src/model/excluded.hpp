// The cost model for excluded-volume (hard-sphere) packings: the paper's
// model with each level pair's count corrected by the Percus-Yevick pair
// structure of the polydisperse mixture (docs/MODEL.md section 8).
#pragma once
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/model.hpp"

namespace hgrid {

/// Walls: which pairs near a wall carry the bulk pair excess (docs/MODEL.md
/// section 8, "Walls").
enum class WallPairs {
  /// None whose scanning centre lies closer to a wall than the largest size
  /// class's mean radius (the layer the largest centres cannot enter, where
  /// the wall's contact layer, already in the one-body profiles, is the
  /// crowding); the rest the bulk excess per random pair.
  depleted_layer,
  /// Every pair the bulk excess per random pair (Kirkwood's superposition of
  /// the wall-particle and particle-particle correlations).
  product,
};
inline const char* to_string(WallPairs w) { return w == WallPairs::depleted_layer ? "layer" : "product"; }
/// "layer" | "product"; anything else throws InputError naming `field`.
WallPairs parse_wall_pairs(const std::string& s, const std::string& field = "wall-pairs");

/// Discretisation of the excluded-volume model. The defaults change T/N by
/// < 1e-3 relative when any of them is doubled, or halved for a step
/// (tests/test_excluded_model).
struct ExcludedOptions {
  int bins_per_level = 6;     // size classes per level (geometric in r)
  double k_max = 15.0;        // largest wave number, in units of 1 / (2 r_min)
  double dk = 0.5;            // wave-number step, in units of pi / (largest window reach)
  int disc_bins_per_level = 4;  // 2D: size classes per level
  double disc_dr = 0.04;      // 2D: r step of the numerical Percus-Yevick solution, in units of 2 r_min
  double disc_range = 3.0;    // 2D: its transforms' range beyond the largest window reach, in largest diameters
  /// 2D: called after each iteration of the numerical solution with the
  /// fraction of the density being solved and the iterations so far (at
  /// most kMaxDiscIterations; seconds per iteration grow like omega^2).
  std::function<void(double, int)> on_iteration;
  /// 2D: if > 0, the most multiply-adds the numerical solution may take
  /// (deterministic, unlike a time limit; kDiscWorkPerSecond of them take
  /// about a second on the reference machine). Beyond it the model refuses
  /// with an InputError naming "excluded-budget": before any iteration when
  /// the budget buys fewer than the fewest iterations a solution has taken.
  double disc_work_budget = 0;
  WallPairs wall_pairs = WallPairs::depleted_layer;  // walls only; not a discretisation
};

/// A box with walls [0, A_1] x [0, A_2] x [0, A_3]: centres of radius r lie
/// in [r, A_k - r]; scans stop at the walls (n_k = ceil(A_k / s) cells of side s).
struct WallBox {
  std::array<double, 3> extent{};
};

/// Most iterations of the 2D numerical Percus-Yevick solution, over its
/// density continuation; past them the model refuses (InputError naming nu).
inline constexpr int kMaxDiscIterations = 1000;
/// Multiply-adds of the 2D numerical solution per second on one core of the
/// reference machine (AMD EPYC Zen 5 VM, docs/record/PERFORMANCE.md: 2.54e8 per
/// iteration at omega = 50 took 37.8 s for 1000 iterations): the default
/// budget of `hgrid count` and Python's count (about a second), and the
/// seconds its refusals state.
inline constexpr double kDiscWorkPerSecond = 6.0e9;

/// Largest number of wave numbers the model evaluates; beyond it (omega above
/// a few thousand) it refuses with an InputError naming omega.
inline constexpr int kMaxWaveNumbers = 1 << 17;

/// T/N and its parts (as evaluate_model) for an excluded-volume packing in
/// 3D with periodic boundaries: each level pair's narrow-phase count is the
/// random-centre count plus n_j times the integral of the search window
/// against h_ij(r) = g_ij(r) - 1 (Percus-Yevick); cell accesses are unchanged.
/// With walls, each pair's random-centre count and cell accesses are those of
/// the walled box (exact for uniform centres in the accessible region) and the
/// Percus-Yevick excess is the bulk one scaled by the same ratio, counting only
/// the scanning centres that opt.wall_pairs charges with it.
/// In 2D (discs: no closed-form Percus-Yevick solution) h_ij comes from the
/// numerical solution (detail::PyNumeric), walls included.
/// Throws InputError for nu >= 1, past the supported omega, and (2D) where the
/// numerical solution does not converge (nu, named with the reachable range).
ModelResult evaluate_excluded_model(const Distribution& dist, const ModelParams& p,
                                    const std::vector<double>& sizes, const ExcludedOptions& opt = {},
                                    const std::optional<WallBox>& walls = std::nullopt);

/// Cell sizes for an excluded-volume packing: starting from `sizes` (e.g. the
/// paper's optimum), a coordinate search in log s_h (steps x1.25 then x1.1,
/// s_L fixed, order kept) that lowers the excluded-volume model's T/N. The
/// number of levels is kept. Returns the sizes and their excluded-volume model.
struct ExcludedSizes {
  std::vector<double> sizes;
  ModelResult model;
  int evaluations = 0;
};
/// on_step(fraction of the search done (an estimate), evaluations so far, best T/N) after each trial.
ExcludedSizes refine_sizes_excluded(const Distribution& dist, const ModelParams& p, std::vector<double> sizes,
                                    const ExcludedOptions& opt = {},
                                    const std::function<void(double, int, double)>& on_step = {});

}  // namespace hgrid
