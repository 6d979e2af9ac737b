#include "hgridlab/scenes/journal.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "hgridlab/scenes/detail/results.hpp"
#include "hgridlab/io/packing_cache.hpp"
#include "hgridlab/base/error.hpp"

namespace hgrid {
namespace {

namespace fs = std::filesystem;

/// Identifies a point within a scene for the resume journal.
std::string point_key(const ScenePoint& p) { return packing_key(p.packing) + to_string(p.search); }

/// True for "<base>.journal.rank<digits>.jsonl": another rank's journal.
bool is_rank_journal(const std::string& name, const std::string& base) {
  const std::string head = base + ".journal.rank", tail = ".jsonl";
  if (name.size() <= head.size() + tail.size() || !name.starts_with(head) || !name.ends_with(tail)) return false;
  return std::all_of(name.begin() + head.size(), name.end() - tail.size(),
                     [](unsigned char c) { return std::isdigit(c) != 0; });
}

/// Reads one journal into done (by point key).
void read_journal(const std::string& path, const Scene& scene, bool report, std::map<std::string, PointResult>& done) {
  std::ifstream in(path);
  std::size_t lineno = 0;
  for (std::string line; std::getline(in, line);) {
    ++lineno;
    try {
      const auto j = nlohmann::json::parse(line);
      if (!j.is_object() || !j.contains("source") || j.at("source") != scene.source) continue;
      PointResult r = detail::result_from_json(j.at("result"));
      detail::check_result(r, scene.grid.K);
      done[point_key(r.point)] = r;
    } catch (const std::exception& e) {
      // A line cut short by the interruption, or one changed by hand: that
      // point is measured again.
      if (report)
        std::cerr << "hgrid run: " << path << ":" << lineno << " not used (" << e.what()
                  << "); that point is measured again\n";
    }
  }
}

}  // namespace

std::string journal_path(const std::string& stem, int rank) {
  return stem + (rank == 0 ? ".journal.jsonl" : ".journal.rank" + std::to_string(rank) + ".jsonl");
}

std::vector<std::string> journal_files(const std::string& stem) {
  const fs::path s(stem);
  const fs::path dir = s.has_parent_path() ? s.parent_path() : fs::path(".");
  const std::string base = s.filename().string();
  std::vector<std::string> ranks;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (is_rank_journal(name, base)) ranks.push_back(name);
  }
  std::sort(ranks.begin(), ranks.end());
  std::vector<std::string> out;
  if (fs::exists(journal_path(stem))) out.push_back(journal_path(stem));
  for (const auto& name : ranks) out.push_back((dir / name).string());
  return out;
}

void remove_journals(const std::string& stem) {
  for (const auto& path : journal_files(stem)) fs::remove(path);
}

Resumed resume(const Scene& scene, const std::string& stem, bool report) {
  std::map<std::string, PointResult> done;
  const std::vector<std::string> files = journal_files(stem);
  for (const auto& path : files) read_journal(path, scene, report, done);
  Resumed out;
  out.results.resize(scene.points.size());
  for (std::size_t i = 0; i < scene.points.size(); ++i) {
    auto it = done.find(point_key(scene.points[i]));
    if (it != done.end()) {
      out.results[i] = it->second;
    } else {
      out.todo.push_back(i);
    }
  }
  if (report && out.todo.size() < scene.points.size()) {
    std::cerr << "hgrid run: " << scene.points.size() - out.todo.size() << " of " << scene.points.size()
              << " points reused from " << files.front();
    if (files.size() > 1) std::cerr << " and " << files.size() - 1 << " more journal file(s) of other ranks";
    std::cerr << "\n";
  }
  return out;
}

void JournalWriter::append(const PointResult& r) {
  if (!out_.is_open()) out_.open(path_, std::ios::app);
  out_ << nlohmann::json{{"source", source_}, {"result", detail::result_to_json(r)}}.dump() << "\n";
  out_.flush();
  if (!out_) throw InputError("journal", "cannot write '" + path_ + "' (disk full?)");
}

}  // namespace hgrid
