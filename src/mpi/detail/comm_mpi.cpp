// mpi/comm.hpp on MPI (compiled when CMake finds MPI).
#include <mpi.h>

#include <climits>
#include <cstring>
#include <cstdlib>
#include <stdexcept>

#include "hgridlab/mpi/comm.hpp"

namespace hgrid::mpi {
namespace {

bool g_active = false;
int g_rank = 0, g_size = 1, g_local_size = 1;

int as_int(std::uint64_t n, const char* what) {
  if (n > static_cast<std::uint64_t>(INT_MAX))
    throw std::runtime_error(std::string("MPI: too many ") + what + " in one message (more than 2^31 - 1)");
  return static_cast<int>(n);
}

}  // namespace

bool built_with_mpi() { return true; }

bool launched_by_mpi() {
  // Open MPI's mpirun, PMIx (Open MPI 4+, srun --mpi=pmix), PMI (MPICH's
  // hydra, srun --mpi=pmi2), and HGRID_MPI=1 to force it.
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(v)) return true;
  const char* force = std::getenv("HGRID_MPI");
  return force && std::string(force) == "1";
}

Session::Session(int& argc, char**& argv) {
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  g_active = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &g_local_size);
  MPI_Comm_free(&node);
}

Session::~Session() {
  if (g_active) MPI_Finalize();
  g_active = false;
}

bool active() { return g_active; }
int rank() { return g_rank; }
int size() { return g_size; }
int local_size() { return g_local_size; }

void barrier() {
  if (g_active) MPI_Barrier(MPI_COMM_WORLD);
}

bool any(bool flag) {
  if (!g_active) return flag;
  int in = flag ? 1 : 0, out = 0;
  MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
  return out != 0;
}

void sum(std::vector<std::uint64_t>& v) {
  if (g_active && !v.empty())
    MPI_Allreduce(MPI_IN_PLACE, v.data(), as_int(v.size(), "values"), MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
}

void sum(std::vector<double>& v) {
  if (g_active && !v.empty())
    MPI_Allreduce(MPI_IN_PLACE, v.data(), as_int(v.size(), "values"), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
}

double max(double v) {
  if (g_active) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return v;
}

std::vector<std::string> gather(const std::string& mine, int root) {
  if (!g_active) return {mine};
  int n = as_int(mine.size(), "bytes");
  std::vector<int> lens(g_rank == root ? g_size : 0);
  MPI_Gather(&n, 1, MPI_INT, lens.data(), 1, MPI_INT, root, MPI_COMM_WORLD);
  std::vector<int> displ(lens.size(), 0);
  std::uint64_t total = 0;
  for (std::size_t r = 0; r < lens.size(); ++r) displ[r] = as_int(total, "bytes"), total += lens[r];
  std::string all(total, '\0');
  MPI_Gatherv(mine.data(), n, MPI_CHAR, all.data(), lens.data(), displ.data(), MPI_CHAR, root, MPI_COMM_WORLD);
  std::vector<std::string> out;
  for (std::size_t r = 0; r < lens.size(); ++r) out.push_back(all.substr(displ[r], lens[r]));
  return out;
}

std::string broadcast(const std::string& s, int root) {
  if (!g_active) return s;
  std::uint64_t n = s.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, root, MPI_COMM_WORLD);
  std::string out = g_rank == root ? s : std::string(n, '\0');
  MPI_Bcast(out.data(), as_int(n, "bytes"), MPI_CHAR, root, MPI_COMM_WORLD);
  return out;
}

void abort(int code) {
  if (g_active) MPI_Abort(MPI_COMM_WORLD, code);
}

namespace detail {

std::vector<std::uint64_t> exchange_counts(const std::vector<std::uint64_t>& send_counts) {
  if (!g_active) return send_counts;
  if (send_counts.size() != static_cast<std::size_t>(g_size)) throw std::logic_error("exchange: one entry per rank");
  std::vector<std::uint64_t> out(send_counts.size());
  MPI_Alltoall(send_counts.data(), 1, MPI_UINT64_T, out.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD);
  return out;
}

void exchange_items(const void* send, const std::vector<std::uint64_t>& send_counts, void* recv,
                    const std::vector<std::uint64_t>& recv_counts, std::size_t item_bytes) {
  std::vector<std::uint64_t> send_at(send_counts.size()), recv_at(recv_counts.size());
  for (std::size_t r = 1; r < send_at.size(); ++r) send_at[r] = send_at[r - 1] + send_counts[r - 1];
  for (std::size_t r = 1; r < recv_at.size(); ++r) recv_at[r] = recv_at[r - 1] + recv_counts[r - 1];
  exchange_items_at(send, send_counts, send_at, recv, recv_counts, recv_at, item_bytes);
}

void exchange_items_at(const void* send, const std::vector<std::uint64_t>& send_counts,
                       const std::vector<std::uint64_t>& send_at, void* recv,
                       const std::vector<std::uint64_t>& recv_counts, const std::vector<std::uint64_t>& recv_at,
                       std::size_t item_bytes) {
  if (!g_active) {
    if (!send_counts.empty() && send_counts[0] > 0)
      std::memcpy(static_cast<char*>(recv) + recv_at[0] * item_bytes,
                  static_cast<const char*>(send) + send_at[0] * item_bytes, send_counts[0] * item_bytes);
    return;
  }
  // Items as one contiguous type, so that counts and offsets count items.
  MPI_Datatype item;
  MPI_Type_contiguous(as_int(item_bytes, "bytes per item"), MPI_BYTE, &item);
  MPI_Type_commit(&item);
  std::vector<int> sc(g_size), sd(g_size), rc(g_size), rd(g_size);
  for (int r = 0; r < g_size; ++r) {
    sc[r] = as_int(send_counts[r], "items"), sd[r] = as_int(send_at[r], "items");
    rc[r] = as_int(recv_counts[r], "items"), rd[r] = as_int(recv_at[r], "items");
  }
  MPI_Alltoallv(send, sc.data(), sd.data(), item, recv, rc.data(), rd.data(), item, MPI_COMM_WORLD);
  MPI_Type_free(&item);
}

}  // namespace detail
}  // namespace hgrid::mpi
