// The resume journal of a scene run: one JSON line per finished point, so
// that a run that was killed loses no measured point. A run on several MPI
// ranks keeps one file per rank (no two processes append to one file); any
// later run, on any number of ranks, reads them all.
#pragma once
#include <fstream>
#include <string>
#include <vector>

#include "hgridlab/scenes/runner.hpp"

namespace hgrid {

/// `<stem>.journal.jsonl` for rank 0 (and a run without MPI),
/// `<stem>.journal.rank<r>.jsonl` for rank r > 0.
std::string journal_path(const std::string& stem, int rank = 0);

/// Every journal file of the stem that exists, rank 0's first.
std::vector<std::string> journal_files(const std::string& stem);

/// Removes every journal file of the stem (after the results are written).
void remove_journals(const std::string& stem);

/// What interrupted runs already measured: results[i] is filled for every
/// point i found in a journal, todo lists the others in scene order.
struct Resumed {
  std::vector<PointResult> results;
  std::vector<std::size_t> todo;
};

/// Reads every journal of the stem: lines of the same scene text (source)
/// are reused, once checked like any input; a line cut short or changed by
/// hand is reported on stderr (when `report`) and its point measured again.
Resumed resume(const Scene& scene, const std::string& stem, bool report);

/// Appends finished points to one journal file, opened with the first point
/// (a run that fails before measuring anything leaves no journal). Flushes
/// every line: a killed run keeps all but the line it was writing. Callers
/// serialise append().
class JournalWriter {
 public:
  JournalWriter(std::string path, std::string source) : path_(std::move(path)), source_(std::move(source)) {}
  /// Throws InputError("journal", ...) when the line cannot be written.
  void append(const PointResult& r);

 private:
  std::string path_, source_;
  std::ofstream out_;
};

}  // namespace hgrid
