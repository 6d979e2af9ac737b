#include "hgridlab/io/packing_cache.hpp"

#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>

#include "hgridlab/base/error.hpp"
#include "hgridlab/io/atomic_file.hpp"
#include "hgridlab/io/packing_file.hpp"

namespace hgrid {

namespace {

/// The cached packing at `path` if it is what check() accepts (""), else
/// nothing (a rejected file is reported when `say` is set).
std::optional<Packing> read_valid(const std::string& path, const std::function<std::string(const Packing&)>& check,
                                  bool say) {
  if (!std::filesystem::exists(path)) return std::nullopt;
  std::string problem;
  try {
    Packing p = read_packing(path);
    problem = check(p);
    if (problem.empty()) return p;
  } catch (const InputError& e) {
    problem = e.what();
  }
  if (say) std::cerr << "hgrid: cached packing " << path << " rejected (" << problem << "); regenerating\n";
  return std::nullopt;
}

}  // namespace

Packing cached_packing(const PackingSpec& s, const std::string& dir) {
  const std::string path = packing_cache_path(s, dir);
  if (auto p = read_valid(path, [&](const Packing& q) { return packing_mismatch(q, s); }, true)) return *std::move(p);
  std::filesystem::create_directories(dir);
  remove_stale_temporaries(dir, kStaleTemporaryAge);
  if (!s.equilibrate) {
    Packing p = generate_packing(s);
    write_packing(path, p);
    return p;
  }
  // An equilibration: resume the furthest stage of the same chain not beyond
  // spec.sweeps, and keep the furthest stage reached for the next run.
  const std::string resume = equilibration_resume_path(s, dir);
  PackingSpec any = s;  // a stage of the chain at any sweeps
  any.sweeps = kMaxEquilibrationSweeps;
  auto from = read_valid(resume, [&](const Packing& q) { return resume_mismatch(q, any); }, false);
  std::uint64_t kept = from ? equilibration_sweeps_done(*from) : 0;
  if (kept > static_cast<std::uint64_t>(s.sweeps)) from.reset();  // further than asked: start afresh, keep it
  if (from) {
    std::cerr << "hgrid: resuming the equilibration from " << resume << " at sweep " << kept << " of " << s.sweeps
              << "\n";
  } else {  // no stage yet: start from the cached placement (sweep 0) if there is one
    PackingSpec placed = s;
    placed.equilibrate = false;
    const std::string start = packing_cache_path(placed, dir);
    from = read_valid(start, [&](const Packing& q) { return resume_mismatch(q, s); }, false);
    if (from) std::cerr << "hgrid: equilibrating the cached placement " << start << "\n";
  }
  const auto keep = [&](const Packing& stage) {
    const std::uint64_t done = equilibration_sweeps_done(stage);
    if (done <= kept) return;
    write_packing(resume, stage);
    kept = done;
  };
  Packing p = generate_packing(s, from ? &*from : nullptr, keep);
  write_packing(path, p);
  keep(p);
  return p;
}

}  // namespace hgrid
