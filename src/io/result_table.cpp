#include "hgridlab/io/result_table.hpp"

#include <cmath>
#include <ostream>
#include <stdexcept>

#include "hgridlab/io/atomic_file.hpp"
#include "hgridlab/io/h5.hpp"

namespace hgrid {
namespace {

std::size_t rows_of(const ResultTable::Column& c) {
  return std::visit([](const auto& v) { return v.size(); }, c.values);
}

void write_h5(const std::string& path, const ResultTable& t) {
  detail::h5_write_file(path, [&](hid_t f) {
    for (const auto& c : t.columns) {
      if (!c.h5) continue;
      if (const auto* num = std::get_if<std::vector<double>>(&c.values))
        detail::h5_write_dataset(f, c.name, *num, {num->size()});
      else
        detail::h5_write_strings(f, c.name, std::get<std::vector<std::string>>(c.values));
    }
    for (const auto& a : t.arrays) {
      const std::vector<hsize_t> dims(a.dims.begin(), a.dims.end());
      std::visit([&](const auto& v) { detail::h5_write_dataset(f, a.name, v, dims); }, a.values);
    }
    const detail::H5Handle root{H5Gopen2(f, "/", H5P_DEFAULT), H5Gclose};
    for (const auto& attr : t.attributes)  // (not a structured binding: clang < 16 cannot capture one)
      std::visit([&](const auto& v) { detail::h5_write_attr(root.id, attr.first, v); }, attr.second);
  });
}

void write_csv(const std::string& path, const ResultTable& t, std::size_t rows) {
  write_stream_atomically(path, [&](std::ostream& out) {
    out.precision(t.csv_precision);
    for (const auto& line : t.csv_comments) out << "# " << line << "\n";
    bool first = true;
    for (const auto& c : t.columns)
      if (c.csv) out << (first ? "" : ",") << c.name, first = false;
    out << "\n";
    for (std::size_t i = 0; i < rows; ++i) {
      first = true;
      for (const auto& c : t.columns) {
        if (!c.csv) continue;
        if (!first) out << ',';
        first = false;
        if (const auto* num = std::get_if<std::vector<double>>(&c.values)) {
          if (std::isnan((*num)[i])) out << "NaN";
          else out << (*num)[i];
        } else {
          out << std::get<std::vector<std::string>>(c.values)[i];
        }
      }
      out << "\n";
    }
  });
}

}  // namespace

void write_result_table(const std::string& stem, const ResultTable& table) {
  const std::size_t rows = table.columns.empty() ? 0 : rows_of(table.columns.front());
  for (const auto& c : table.columns)
    if (rows_of(c) != rows)
      throw std::invalid_argument("write_result_table: column " + c.name + " has " + std::to_string(rows_of(c)) +
                                  " rows, " + table.columns.front().name + " " + std::to_string(rows));
  write_h5(stem + ".h5", table);
  write_csv(stem + ".csv", table, rows);
}

}  // namespace hgrid
