#include <cstdlib>
#include <stdexcept>
#include <string>

#include "hgridlab/base/error.hpp"
#include "hgridlab/mpi/comm.hpp"

namespace hgrid::mpi {

int launched_ranks() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* n = std::getenv(v)) {
      const int k = std::atoi(n);
      if (k > 1) return k;
    }
  return 1;
}

}  // namespace hgrid::mpi

namespace hgrid::mpi::detail {

void agree(std::exception_ptr mine) {
  if (!active()) {
    if (mine) std::rethrow_exception(mine);
    return;
  }
  if (!any(static_cast<bool>(mine))) return;
  // What failed where: "<kind><message>" per rank (kind: I input, E other,
  // P peer, - none).
  std::string said = "-";
  if (mine) {
    try {
      std::rethrow_exception(mine);
    } catch (const PeerFailed&) {
      said = "P";
    } catch (const InputError& e) {
      said = std::string("I") + e.field() + '\n' + e.what();
    } catch (const std::exception& e) {
      said = std::string("E") + e.what();
    } catch (...) {
      said = "Eunknown error";
    }
  }
  const std::vector<std::string> all = gather(said, 0);
  // Every rank needs the exit status: 2 for bad input, else 1.
  const bool input = broadcast(rank() == 0 ? [&] {
    for (const auto& s : all)
      if (s[0] == 'I' || s[0] == 'E') return std::string(1, s[0]);
    return std::string("E");
  }() : std::string()) == "I";
  if (rank() != 0) throw PeerFailed(input ? 2 : 1);
  for (std::size_t r = 0; r < all.size(); ++r) {
    const std::string& s = all[r];
    if (s[0] != 'I' && s[0] != 'E') continue;
    const std::string prefix = r == 0 ? "" : "rank " + std::to_string(r) + ": ";
    if (s[0] == 'I') {
      const std::size_t nl = s.find('\n');
      const std::string field = s.substr(1, nl - 1);
      const std::string what = s.substr(nl + 1);
      // InputError prefixes "field: "; keep the message as the rank said it.
      throw InputError(prefix + field, what.substr(std::min(what.size(), field.size() + 2)));
    }
    throw std::runtime_error(prefix + s.substr(1));
  }
  throw PeerFailed(1);
}

}  // namespace hgrid::mpi::detail
