#include "experiment/timing.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "grid/dispatch.hpp"
#include "grid/error.hpp"
#include "grid/hgrid.hpp"

namespace hgrid {

QueryTiming time_query(const Packing& p, const GridParams& g, const TimingOptions& opt) {
  if (opt.min_repeats < 1 || opt.max_repeats < opt.min_repeats)
    throw InputError("repeat", "need 1 <= min_repeats <= max_repeats");
  using Clock = std::chrono::steady_clock;
  const auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  QueryTiming out;
  dispatch(p.d, p.boundary, [&](auto dim, auto bnd) {
    constexpr int D = decltype(dim)::value;
    constexpr Boundary B = decltype(bnd)::value;
    const auto spheres = p.spheres<D>();
    {
      const HGrid<D, B> grid(spheres, p.extent<D>(), g);
      out.counts = grid.template for_each_pair<Counted>([](std::uint32_t, std::uint32_t) {});
      out.sizes = grid.sizes();
      out.build_work = build_work(grid);
    }
    std::vector<double> queries;
    double total = 0, best_build = 1e300;
    struct alignas(64) Slot {  // pairs found per thread (one cache line each)
      std::uint64_t n = 0;
    };
    std::vector<Slot> found(static_cast<std::size_t>(resolve_threads(g.threads)));
    while (static_cast<int>(queries.size()) < opt.max_repeats &&
           (static_cast<int>(queries.size()) < opt.min_repeats || total < opt.min_seconds)) {
      auto t0 = Clock::now();
      const HGrid<D, B> grid(spheres, p.extent<D>(), g);
      best_build = std::min(best_build, since(t0));
      for (auto& f : found) f.n = 0;
      t0 = Clock::now();
      grid.for_each_pair([&found](int t, std::uint32_t, std::uint32_t) { ++found[static_cast<std::size_t>(t)].n; });
      const double t = since(t0);
      std::uint64_t pairs = 0;
      for (const auto& f : found) pairs += f.n;
      if (pairs != out.counts.contacts)
        throw std::logic_error("time_query: uncounted and counted queries found different pairs");
      queries.push_back(t);
      total += t;
    }
    std::sort(queries.begin(), queries.end());
    out.query_seconds = queries.front();
    out.median_query_seconds = queries[queries.size() / 2];
    out.build_seconds = best_build;
    out.repeats = static_cast<int>(queries.size());
  });
  return out;
}

}  // namespace hgrid
