// The few MPI operations hgridlab needs, behind plain C++ types. Built on
// Open MPI when CMake finds MPI (HGRID_MPI=ON, the default); without it (or
// when the tool was not started by mpirun/srun) every function acts as the
// one rank of a one-rank run, so the same code runs with and without MPI.
#pragma once
#include <cstdint>
#include <exception>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "hgridlab/grid/uninit_vector.hpp"

namespace hgrid::mpi {

/// True when this build has MPI.
bool built_with_mpi();

/// True when an MPI launcher started this process (mpirun or mpiexec of Open
/// MPI or MPICH, Slurm's srun): the environment variables they set.
bool launched_by_mpi();

/// The number of processes a launcher says it started (OMPI_COMM_WORLD_SIZE,
/// PMI_SIZE; 1 when neither is set), whether or not this build has MPI: a
/// build without MPI started as several ranks would run as several copies.
int launched_ranks();

/// MPI for the lifetime of this object: initialised (funneled threads) only
/// when launched_by_mpi(), so that a plain run never starts MPI; finalised
/// by the destructor. One per process, in main().
class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

/// True inside a Session that initialised MPI.
bool active();
/// This process's rank and the number of ranks (0 and 1 without MPI).
int rank();
int size();
/// Ranks of this run on this machine (1 without MPI).
int local_size();

/// Waits for every rank.
void barrier();
/// True on every rank if `flag` is true on any.
bool any(bool flag);
/// Element-wise sums over the ranks, on every rank.
void sum(std::vector<std::uint64_t>& v);
void sum(std::vector<double>& v);
/// The largest value over the ranks, on every rank.
double max(double v);
/// Every rank's string in rank order on `root` (empty on the others).
std::vector<std::string> gather(const std::string& mine, int root = 0);
/// `s` of `root` on every rank.
std::string broadcast(const std::string& s, int root = 0);
/// Ends every rank of the run (after a rank-local error the others cannot
/// learn of); returns only without MPI (then the caller exits).
void abort(int code);

namespace detail {
/// How many items every rank sends here, given how many this one sends to each.
std::vector<std::uint64_t> exchange_counts(const std::vector<std::uint64_t>& send_counts);
/// The items themselves (item_bytes each): `send` holds send_counts[0] items
/// for rank 0, then those for rank 1, ...; recv has room for the sum of
/// recv_counts and is filled in rank order.
void exchange_items(const void* send, const std::vector<std::uint64_t>& send_counts, void* recv,
                    const std::vector<std::uint64_t>& recv_counts, std::size_t item_bytes);
/// Same, with each rank's items at an offset of their own (in items):
/// send_counts[r] items from send + send_at[r] to rank r, recv_counts[r]
/// from rank r into recv + recv_at[r].
void exchange_items_at(const void* send, const std::vector<std::uint64_t>& send_counts,
                       const std::vector<std::uint64_t>& send_at, void* recv,
                       const std::vector<std::uint64_t>& recv_counts, const std::vector<std::uint64_t>& recv_at,
                       std::size_t item_bytes);
}  // namespace detail

/// All-to-all of trivially copyable items: `items` holds counts[0] items for
/// rank 0, then counts[1] for rank 1, ... (counts has size() entries).
/// Returns what every rank sent to this one, in rank order.
template <class T>
UninitVector<T> all_to_all(std::span<const T> items, const std::vector<std::uint64_t>& counts) {
  static_assert(std::is_trivially_copyable_v<T>);
  const std::vector<std::uint64_t> recv_counts = detail::exchange_counts(counts);
  std::uint64_t total = 0;
  for (auto c : recv_counts) total += c;
  UninitVector<T> out(total);
  detail::exchange_items(items.data(), counts, out.data(), recv_counts, sizeof(T));
  return out;
}

/// Thrown by collective() on the ranks that stay silent about another
/// rank's failure; `status` is the exit status the tool returns.
struct PeerFailed : std::exception {
  int status;
  explicit PeerFailed(int s) : status(s) {}
  const char* what() const noexcept override { return "another rank failed"; }
};

namespace detail {
/// The agreement step of collective(): rethrows on rank 0 the error of the
/// lowest failing rank (an InputError stays one, its message prefixed with
/// "rank r: " when r > 0); the other ranks throw PeerFailed.
void agree(std::exception_ptr mine);
}  // namespace detail

/// Runs fn on every rank, then lets every rank learn whether it failed on
/// any: if so, rank 0 throws that error (it alone reports it) and the others
/// throw PeerFailed, so that no rank waits forever for a failed one. Every
/// rank must call it at the same point.
template <class Fn>
void collective(Fn&& fn) {
  std::exception_ptr e;
  try {
    fn();
  } catch (...) {
    e = std::current_exception();
  }
  detail::agree(e);
}

}  // namespace hgrid::mpi
