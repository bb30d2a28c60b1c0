#pragma once
// The MPI world of a run: rank, size and the few collectives the distributed force pass and the
// run loop need. A build without MPI, and a process not started by mpirun, is one rank: every
// call below is then a no-op that returns its input.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/exact_sum.hpp"

namespace periadapt::mpi {

// Initializes MPI (and Zoltan) when this process was started by mpirun with more than one
// rank; finalizes at exit. One per process, in main.
class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

bool built_with_mpi();
int rank();
int size();
inline bool distributed() { return size() > 1; }

// The other ranks have left (a command that rank 0 runs alone): from here on this process is a
// world of one, so no collective waits for them.
void continue_alone();

// Ends every rank with exit code `code` (an error one rank met alone).
[[noreturn]] void abort(int code);

// Largest value over the ranks.
long max(long v);
double max_real(double v);
// Sum over the ranks.
double sum_real(double v);
// Adds the ranks' exact accumulators: afterwards every rank holds the exact sum of every rank's
// terms, the same bits as one accumulator that took them all (order-free sums).
void sum_exact(ExactSum* sums, std::size_t count);
// The lowest rank's non-empty `mine`, on every rank; empty when every rank's is (an error some
// ranks met, which all then report alike).
std::string first_text(const std::string& mine);
// Each rank's `mine` concatenated in rank order, and (counts) how many each gave.
template <class T>
std::vector<T> all_gather(const std::vector<T>& mine, std::vector<int>* counts = nullptr);
// The same into `out`, whose storage is reused (a per-step exchange then neither allocates nor
// clears its buffer).
template <class T>
void all_gather_into(const std::vector<T>& mine, std::vector<T>& out,
                     std::vector<int>* counts = nullptr);

// Personalized exchange: send[r] goes to rank r; returns what every rank sent this one,
// concatenated in rank order, and (counts) how many came from each.
template <class T>
std::vector<T> all_to_all(const std::vector<std::vector<T>>& send, std::vector<int>* counts = nullptr);

// Each rank's `mine` concatenated in rank order on rank 0 alone (the others get an empty
// vector): what one rank writes, without a copy of it on every rank.
template <class T>
std::vector<T> gather_to_root(const std::vector<T>& mine);

// Where this rank's segment starts in a rank-ordered gather with counts[r] entries from rank r.
inline std::size_t own_offset(const std::vector<int>& counts) {
  std::size_t at = 0;
  for (int r = 0; r < rank(); ++r) at += static_cast<std::size_t>(counts[static_cast<std::size_t>(r)]);
  return at;
}

// Point to point with a few peers: sends send[k] to peers[k] and receives recv[k] from it, whose
// sizes the caller set (every rank lists the other as a peer). No-op on one rank.
void exchange_with(const std::vector<int>& peers, const std::vector<std::vector<double>>& send,
                   std::vector<std::vector<double>>& recv);

}  // namespace periadapt::mpi
