// The core's umbrella header alone (no HDF5 on the include path): a contact
// list of three spheres, one touching pair.
#include <cstdio>
#include <vector>

#include <hgridlab/core.hpp>

int main() {
  using namespace hgrid;
  const std::vector<Sphere<3>> spheres{{{1.0, 1.0, 1.0}, 0.5}, {{1.8, 1.0, 1.0}, 0.5}, {{5.0, 5.0, 5.0}, 1.0}};
  ContactList<3> list(ListBox<3>{{10, 10, 10}, {}, {true, true, true}}, ContactListParams{});
  list.update(spheres);
  std::printf("hgridlab %s core: %zu contact(s)\n", HGRIDLAB_VERSION, list.contacts());
  return list.contacts() == 1 ? 0 : 1;
}
