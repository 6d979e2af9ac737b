// The result file pair (io/result_table): the CSV's exact text, the HDF5
// file's datasets and attributes read back, and nothing written for a table
// whose columns disagree.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "cli_support.hpp"
#include "hgridlab/io/h5.hpp"
#include "hgridlab/io/result_table.hpp"

namespace hgrid::test {
namespace {

class ResultTableFiles : public TempDir {};

ResultTable small_table() {
  ResultTable t;
  t.csv_precision = 4;
  t.csv_comments = {"scene=x scale=smoke"};
  t.columns = {{"search", std::vector<std::string>{"topdown", "bottomup"}},
               {"n", std::vector<double>{1000, 30000}},
               {"T_over_N", std::vector<double>{12.34567, std::nan("")}},
               {"sizes", std::vector<std::string>{"1;2", "1;2;4"}, true, false}};
  t.arrays = {{"particles_per_level", std::vector<std::uint64_t>{1, 2, 3, 4, 0, 6}, {2, 3}}};
  t.attributes = {{"scene", std::string("x")}, {"K", std::vector<double>{0.2}}, {"seed", std::int64_t{7}}};
  return t;
}

TEST_F(ResultTableFiles, CsvTextAndHdf5ContentAreTheTable) {
  const std::string stem = path("r");
  write_result_table(stem, small_table());
  std::ifstream csv(stem + ".csv");
  std::stringstream text;
  text << csv.rdbuf();
  EXPECT_EQ(text.str(),
            "# scene=x scale=smoke\n"
            "search,n,T_over_N,sizes\n"
            "topdown,1000,12.35,1;2\n"
            "bottomup,3e+04,NaN,1;2;4\n");

  std::lock_guard<std::recursive_mutex> lock(detail::h5_mutex());
  const detail::H5Handle f{H5Fopen((stem + ".h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  ASSERT_GE(f.id, 0);
  const auto n = detail::h5_read_rows(f.id, "n", 0, 2, 1, stem);
  EXPECT_EQ(n, (std::vector<double>{1000, 30000}));
  const auto t = detail::h5_read_rows(f.id, "T_over_N", 0, 2, 1, stem);
  EXPECT_EQ(t[0], 12.34567);  // full precision: the CSV's digits are for reading
  EXPECT_TRUE(std::isnan(t[1]));
  EXPECT_EQ(detail::h5_read_rows(f.id, "particles_per_level", 0, 2, 3, stem),
            (std::vector<double>{1, 2, 3, 4, 0, 6}));
  EXPECT_TRUE(H5Lexists(f.id, "search", H5P_DEFAULT) > 0);
  EXPECT_FALSE(H5Lexists(f.id, "sizes", H5P_DEFAULT) > 0);  // a CSV-only column
  const detail::H5Handle root{H5Gopen2(f.id, "/", H5P_DEFAULT), H5Gclose};
  EXPECT_EQ(detail::h5_read_string_attr(root.id, "scene", stem), "x");
  EXPECT_EQ(detail::h5_read_double_attr(root.id, "K", stem), (std::vector<double>{0.2}));
  EXPECT_EQ(detail::h5_read_double_attr(root.id, "seed", stem), (std::vector<double>{7}));
}

TEST_F(ResultTableFiles, ColumnsOfUnequalLengthWriteNothing) {
  ResultTable t = small_table();
  std::get<std::vector<double>>(t.columns[1].values).push_back(5);
  EXPECT_THROW(write_result_table(path("r"), t), std::invalid_argument);
  EXPECT_TRUE(fs::is_empty(dir_));
}

}  // namespace
}  // namespace hgrid::test
