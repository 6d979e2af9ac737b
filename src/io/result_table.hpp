// A result file pair, <stem>.h5 and <stem>.csv, from one table: the one way
// the scene runner and the DPM scenes write what they measured (HDF5 for the
// data with its parameters attached, CSV for plots and diffs).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace hgrid {

/// What a result file holds.
struct ResultTable {
  /// One value per row: a CSV column and/or a 1-D HDF5 dataset.
  struct Column {
    std::string name;
    std::variant<std::vector<double>, std::vector<std::string>> values;
    bool csv = true, h5 = true;
  };
  /// An HDF5 dataset of any shape (row-major `dims`), e.g. [point][level].
  struct Array {
    std::string name;
    std::variant<std::vector<double>, std::vector<std::uint64_t>> values;
    std::vector<std::uint64_t> dims;
  };
  /// An attribute of the HDF5 file's root group.
  using Attribute = std::pair<std::string, std::variant<std::string, std::vector<double>, std::int64_t>>;

  std::vector<Column> columns;        // the CSV's columns in this order; every column has as many rows
  std::vector<Array> arrays;          // HDF5 only
  std::vector<Attribute> attributes;  // HDF5 only
  std::vector<std::string> csv_comments;  // CSV lines "# <comment>" before the header
  int csv_precision = 17;             // significant digits of the CSV's numbers (NaN is written "NaN")
};

/// Writes `<stem>.h5` (columns marked h5 as datasets, then the arrays, then the
/// attributes) and `<stem>.csv` (comments, header, one line per row), each
/// through a temporary file: a failure leaves neither partly written.
/// Columns of unequal length throw std::invalid_argument before anything is written.
void write_result_table(const std::string& stem, const ResultTable& table);

}  // namespace hgrid
