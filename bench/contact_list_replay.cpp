// The C++ half of bench/python_overhead.py: the same contact-list loop as the
// Python one, through the C++ API, on the same arrays (read from raw float64
// files: x0 (n x d), v (n x d), radii (n), box (d)): at step t the positions are
// x0 + t v; each step is update(positions, radii) and the contacts copied to
// an (M, 2) array. Prints the fastest of `reps` runs' seconds per step.
//   build/contact_list_replay DIR d n steps skin reps
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "hgridlab/contacts/contact_list.hpp"

namespace {

std::vector<double> read(const std::string& path, std::size_t count) {
  std::vector<double> out(count);
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(count * sizeof(double)));
  if (!in) {
    std::fprintf(stderr, "contact_list_replay: cannot read %zu values from %s\n", count, path.c_str());
    std::exit(2);
  }
  return out;
}

template <int D>
double run(const std::string& dir, std::size_t n, int steps, double skin) {
  const auto x0 = read(dir + "/x0.bin", n * D), v = read(dir + "/v.bin", n * D), r = read(dir + "/r.bin", n),
             b = read(dir + "/box.bin", D);
  hgrid::ListBox<D> box;
  for (int k = 0; k < D; ++k) box.side[k] = b[k], box.periodic[k] = true;
  hgrid::ContactList<D> list(box, hgrid::ContactListParams{{}, hgrid::Search::bottom_up, 1, skin, 0.0});
  std::vector<double> x(n * D);
  std::vector<std::uint32_t> pairs;
  double seconds = 0;  // update + pairs only, as the Python loop times them
  for (int t = 0; t < steps; ++t) {
    for (std::size_t i = 0; i < n * D; ++i) x[i] = x0[i] + t * v[i];  // as numpy's x0 + t * v
    const auto t1 = std::chrono::steady_clock::now();
    list.update(x, r);
    pairs.resize(2 * list.contacts());
    std::uint32_t* o = pairs.data();
    list.for_each_contact([&](std::uint32_t i, std::uint32_t j) { *o++ = i, *o++ = j; });
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  }
  return seconds / steps;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr, "usage: contact_list_replay DIR d n steps skin reps\n");
    return 2;
  }
  const std::string dir = argv[1];
  const int d = std::atoi(argv[2]), steps = std::atoi(argv[4]), reps = std::atoi(argv[6]);
  const std::size_t n = std::strtoull(argv[3], nullptr, 10);
  const double skin = std::atof(argv[5]);
  double best = 1e300;
  for (int k = 0; k < reps; ++k) best = std::min(best, d == 2 ? run<2>(dir, n, steps, skin) : run<3>(dir, n, steps, skin));
  std::printf("%.9g\n", best);
}
