#include "hgridlab/io/peer_settings.hpp"

#include <charconv>
#include <cmath>

#include "hgridlab/io/lammps_export.hpp"

namespace hgrid {

std::vector<double> rounded_up_sizes(const std::vector<double>& sizes) {
  std::vector<double> out;
  for (double s : sizes) {
    const double scale = std::pow(10.0, kPasteDigits - 1 - std::floor(std::log10(s)));
    double r = std::ceil(s * scale) / scale;
    if (r < s) r = std::nextafter(r, INFINITY);  // the division rounded below s
    if (!out.empty() && !(r > out.back())) return sizes;
    out.push_back(r);
  }
  return out;
}

std::string shortest_number(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::vector<std::string> lammps_settings(const std::vector<double>& sizes, double skin) {
  return {"neighbor " + shortest_number(skin) + " multi", lammps_collection_interval(rounded_up_sizes(sizes)),
          "comm_modify mode multi reduce/multi"};
}

std::vector<std::string> mercurydpm_settings(const std::vector<double>& sizes, Search search) {
  const std::vector<double> s = rounded_up_sizes(sizes);
  std::string list;
  for (double v : s) list += (list.empty() ? "" : ", ") + shortest_number(v);
  return {std::string("setHGridMethod(") + (search == Search::top_down ? "TOPDOWN" : "BOTTOMUP") + ");",
          "setHGridDistribution(USER);",
          "setHGridMaxLevels(" + std::to_string(s.size()) + ");",
          "// in your class derived from Mercury2D/Mercury3D:",
          "Mdouble userHGridCellSize(unsigned int level) override {",
          "  static const Mdouble sizes[] = {" + list + "};",
          "  return sizes[level];",
          "}"};
}

}  // namespace hgrid
