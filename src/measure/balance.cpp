#include "hgridlab/measure/balance.hpp"

#include <algorithm>
#include <functional>
#include <numeric>
#include <optional>
#include <queue>

#include "hgridlab/grid/dispatch.hpp"
#include "hgridlab/grid/tilted.hpp"
#include "hgridlab/grid/hgrid.hpp"

namespace hgrid {

double simulated_makespan(std::span<const double> costs, int threads) {
  if (threads < 1) throw InputError("threads", "must be >= 1");
  std::priority_queue<double, std::vector<double>, std::greater<double>> free_at;  // when each thread is free
  for (int t = 0; t < threads; ++t) free_at.push(0.0);
  double end = 0;
  for (const double c : costs) {
    const double start = free_at.top();
    free_at.pop();
    free_at.push(start + c);
    end = std::max(end, start + c);
  }
  return end;
}

std::vector<Balance> simulate_balance(const Packing& p, const GridParams& g, std::span<const int> threads,
                                      const BalanceCost& cost) {
  std::vector<Balance> out;
  dispatch(p.d, p.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    constexpr Boundary B = decltype(bnd)::value;
    const auto spheres = p.spheres<D>();
    GridParams one = g;
    one.threads = 1;
    // A tilted box: the pieces of its mapped grid (grid/tilted.hpp), which does the work.
    std::optional<TiltedHGrid<D>> tilted;
    std::optional<HGrid<D, B>> plain;
    if (p.tilted()) tilted.emplace(spheres, p.tilted_box<D>(), one);
    else plain.emplace(spheres, p.extent<D>(), one);
    const auto run = [&](const auto& grid) {
      for (const int P : threads) {
        const auto pieces = g.search == Search::top_down ? grid.template counted_pieces<Search::top_down>(P)
                                                         : grid.template counted_pieces<Search::bottom_up>(P);
        std::vector<double> costs;
        for (const auto& piece : pieces) {
          if (cost.coef) {
            TimeTerms t = counted_time_terms(piece.counts, BuildWork{});
            t.particles = static_cast<double>(piece.particles);
            t.level_steps = 0;
            costs.push_back(predict_seconds(*cost.coef, t).query);
          } else {
            costs.push_back(piece.counts.cost(cost.K));
          }
        }
        const double total = std::accumulate(costs.begin(), costs.end(), 0.0);
        const double largest = costs.empty() ? 0.0 : *std::max_element(costs.begin(), costs.end());
        Balance b;
        b.threads = P;
        b.pieces = pieces.size();
        b.imbalance = total > 0 ? simulated_makespan(costs, P) / (total / P) - 1 : 0.0;
        b.largest_piece = total > 0 ? largest / total * P : 0.0;
        out.push_back(b);
      }
    };
    if (tilted) run(tilted->mapped_grid());
    else run(*plain);
  });
  return out;
}

}  // namespace hgrid
