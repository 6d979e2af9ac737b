// mpi/comm.hpp without MPI (CMake found none, or HGRID_MPI=OFF): one rank.
#include <cstring>

#include "hgridlab/mpi/comm.hpp"

namespace hgrid::mpi {

bool built_with_mpi() { return false; }
bool launched_by_mpi() { return false; }
Session::Session(int&, char**&) {}
Session::~Session() = default;
bool active() { return false; }
int rank() { return 0; }
int size() { return 1; }
int local_size() { return 1; }
void barrier() {}
bool any(bool flag) { return flag; }
void sum(std::vector<std::uint64_t>&) {}
void sum(std::vector<double>&) {}
double max(double v) { return v; }
std::vector<std::string> gather(const std::string& mine, int) { return {mine}; }
std::string broadcast(const std::string& s, int) { return s; }
void abort(int) {}

namespace detail {
std::vector<std::uint64_t> exchange_counts(const std::vector<std::uint64_t>& send_counts) { return send_counts; }
void exchange_items(const void* send, const std::vector<std::uint64_t>& send_counts, void* recv,
                    const std::vector<std::uint64_t>&, std::size_t item_bytes) {
  if (!send_counts.empty() && send_counts[0] > 0) std::memcpy(recv, send, send_counts[0] * item_bytes);
}
void exchange_items_at(const void* send, const std::vector<std::uint64_t>& send_counts,
                       const std::vector<std::uint64_t>& send_at, void* recv, const std::vector<std::uint64_t>&,
                       const std::vector<std::uint64_t>& recv_at, std::size_t item_bytes) {
  if (!send_counts.empty() && send_counts[0] > 0)
    std::memcpy(static_cast<char*>(recv) + recv_at[0] * item_bytes,
                static_cast<const char*>(send) + send_at[0] * item_bytes, send_counts[0] * item_bytes);
}
}  // namespace detail
}  // namespace hgrid::mpi
