// hgrid pairs: every overlapping pair of a packing file, by the HGrid or
// by brute force.
#include <memory>
#include <vector>

#include "grid_options.hpp"
#include "hgridlab/measure/pairs.hpp"

namespace hgrid::cli {
namespace {

void run_pairs(const GridOptions& o, bool brute) {
  if (o.decompose) {
    if (brute) throw InputError("brute", "not with --decompose");
    return run_decomposed_pairs(o.file, decomposed_params(o));
  }
  const Packing p = read_grid_packing(o);
  const GridParams g = brute ? GridParams{} : resolve(o, p, 0.2);
  // One writer per thread; each writes whole lines, so the lines of several
  // threads never mix (their order does differ between runs).
  std::vector<PairWriter> out(static_cast<std::size_t>(brute ? 1 : resolve_threads(g.threads)));
  const auto write = [&](int t, std::uint32_t i, std::uint32_t j) { out[static_cast<std::size_t>(t)](i, j); };
  if (brute)
    for_each_packing_pair_brute(p, write);
  else
    for_each_packing_pair(p, g, write);
}

}  // namespace

void register_pairs_commands(CLI::App& app) {
  {
    auto o = std::make_shared<GridOptions>();
    auto brute = std::make_shared<bool>(false);
    auto* sub = app.add_subcommand("pairs", "print every overlapping pair 'i j' (0-based, i < j), one per line");
    add_grid_options(sub, *o);
    sub->add_flag("--brute", *brute, "use the O(N^2) brute force instead of the HGrid");
    sub->callback([o, brute] { run_pairs(*o, *brute); });
  }
}

}  // namespace hgrid::cli
