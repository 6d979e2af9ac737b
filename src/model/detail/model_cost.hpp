// Fast evaluation of the cost T/N and its gradient with respect to the cell
// sizes; shared by evaluate_model() and the cell-size optimiser.
#pragma once
#include <array>
#include <vector>

#include "hgridlab/model/distribution.hpp"
#include "hgridlab/model/model.hpp"

namespace hgrid::detail {

class CostModel {
 public:
  static constexpr int kMaxD = 3;

  CostModel(const Distribution& dist, const ModelParams& p);  // validates p

  const Distribution& dist() const { return dist_; }
  const ModelParams& params() const { return p_; }
  double s0() const { return 2.0 * dist_.r_min(); }   // boundary size s_0
  double sL() const { return 2.0 * dist_.r_max(); }   // largest size s_L
  double mean_volume() const { return vp_; }          // V_p

  /// T/N for sizes s_1..s_L (no validation: callers check).
  double total(const std::vector<double>& s) const;
  /// T/N and dT/ds_k for k = 1..L (grad resized to L; the last entry is the
  /// derivative with s_L free, which callers with s_L fixed ignore).
  double total_and_gradient(const std::vector<double>& s, std::vector<double>& grad) const;
  /// Full breakdown per level.
  ModelResult detailed(const std::vector<double>& s) const;

 private:
  struct Level {
    double s, P, m;
    std::array<double, kMaxD + 1> M;  // partial moments M_i = int r^i f over the level
  };
  void fill_levels(const std::vector<double>& s, std::vector<Level>& lv) const;

  const Distribution& dist_;
  ModelParams p_;
  int nc_;                                // neighbour cells, (3^d - 1) / 2
  double vp_, c_;                         // V_p and nu / V_p
  std::array<double, kMaxD + 1> coef_{};  // 2^d binom(d, i): (2 + 2r/s)^d = sum coef_i (r/s)^i
};

}  // namespace hgrid::detail
