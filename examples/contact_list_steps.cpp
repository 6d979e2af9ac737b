// A soft-sphere gas stepped with velocity Verlet, its contacts from a
// hgrid::ContactList kept between the steps: a box periodic in x and y,
// walled in z (a slab; LAMMPS's `boundary p p f`). Needs hgridlab::core only.
//   cmake -S examples -B build-examples && cmake --build build-examples
//   build-examples/contact_list_steps
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <hgridlab/contacts/contact_list.hpp>

int main() {
  using namespace hgrid;
  const int per_axis = 16;  // a 16^3 lattice of sites 3.75 apart: no overlap at the start
  const std::size_t n = per_axis * per_axis * per_axis;
  const double side = 60.0, dt = 0.01, stiffness = 100.0;
  ListBox<3> box{{side, side, side}, {0.0, 0.0, 0.0}, {true, true, false}};

  std::mt19937_64 rng(1);  // the seed: the same run every time
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 0.5);
  std::vector<Sphere<3>> s(n);
  std::vector<std::array<double, 3>> v(n), f(n);
  for (std::size_t i = 0; i < n; ++i) {
    s[i].r = 0.5 + u(rng);  // radii in [0.5, 1.5)
    const std::size_t site[3] = {i % per_axis, i / per_axis % per_axis, i / (per_axis * per_axis)};
    for (int k = 0; k < 3; ++k) s[i].x[k] = (site[k] + 0.5) * side / per_axis, v[i][k] = g(rng);
  }

  // [readme]
  // Candidates within r_i + r_j + 0.5, rebuilt only when a particle may have crossed that skin.
  ContactList<3> list(box, ContactListParams{.sizes = {}, .search = Search::bottom_up, .threads = 1, .skin = 0.5});
  const auto forces = [&] {
    list.update(s);
    for (auto& fi : f) fi = {0.0, 0.0, 0.0};
    list.for_each_contact([&](std::uint32_t i, std::uint32_t j) {  // every touching pair, i < j
      const auto d = list.displacement(i, j);                      // x_j - x_i, minimum image
      const double dist = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const double push = stiffness * (s[i].r + s[j].r - dist) / dist;
      for (int k = 0; k < 3; ++k) f[i][k] -= push * d[k], f[j][k] += push * d[k];
    });
  };
  // [/readme]

  forces();
  for (int step = 0; step < 1000; ++step) {
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) {
        v[i][k] += 0.5 * dt * f[i][k];  // unit masses
        s[i].x[k] += dt * v[i][k];      // periodic axes may leave the box: the list wraps them
      }
    for (std::size_t i = 0; i < n; ++i)  // hard walls at z = 0 and z = side: the centres bounce off
      if ((s[i].x[2] < s[i].r && v[i][2] < 0) || (s[i].x[2] > side - s[i].r && v[i][2] > 0)) v[i][2] = -v[i][2];
    forces();
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) v[i][k] += 0.5 * dt * f[i][k];
  }
  const ContactListStats& st = list.stats();
  std::printf("%llu steps, %llu list builds, %zu contacts now, %.1f us per step of contact detection\n",
              static_cast<unsigned long long>(st.steps), static_cast<unsigned long long>(st.builds), list.contacts(),
              1e6 * st.seconds_per_step());
  return st.builds < st.steps ? 0 : 1;
}
