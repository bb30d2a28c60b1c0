#include "parallel/mpi_env.hpp"

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <stdexcept>
#include <string>

#ifdef PERIADAPT_HAVE_MPI
#include <mpi.h>
#include <zoltan.h>
#endif

namespace periadapt::mpi {

namespace {
bool g_active = false;  // MPI initialized by Session, more than one rank
int g_rank = 0, g_size = 1;

#ifdef PERIADAPT_HAVE_MPI
// Started by mpirun (Open MPI or MPICH/Hydra set these): a singleton run never initializes MPI,
// so serial runs, tests and sanitizer builds stay free of it.
bool launched_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* s = std::getenv(v)) return std::atoi(s) > 1;
  return false;
}

template <class T>
MPI_Datatype type_of();
template <>
MPI_Datatype type_of<double>() { return MPI_DOUBLE; }
template <>
MPI_Datatype type_of<std::uint32_t>() { return MPI_UINT32_T; }
template <>
MPI_Datatype type_of<std::uint64_t>() { return MPI_UINT64_T; }
template <>
MPI_Datatype type_of<int>() { return MPI_INT; }
#endif
}  // namespace

Session::Session(int& argc, char**& argv) {
#ifdef PERIADAPT_HAVE_MPI
  if (!launched_by_mpirun()) return;
  int provided = 0;
  // Only the main thread calls MPI (OpenMP threads run the kernels between the calls).
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
  float version = 0;
  if (Zoltan_Initialize(argc, argv, &version) != ZOLTAN_OK)
    throw std::runtime_error("Zoltan_Initialize failed");
  g_active = g_size > 1;
#else
  (void)argc;
  (void)argv;
#endif
}

Session::~Session() {
#ifdef PERIADAPT_HAVE_MPI
  int init = 0, fin = 0;
  MPI_Initialized(&init);
  MPI_Finalized(&fin);
  if (init && !fin) MPI_Finalize();
#endif
}

bool built_with_mpi() {
#ifdef PERIADAPT_HAVE_MPI
  return true;
#else
  return false;
#endif
}

int rank() { return g_rank; }
int size() { return g_active ? g_size : 1; }

void continue_alone() { g_active = false; }

void abort(int code) {
#ifdef PERIADAPT_HAVE_MPI
  if (g_active) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

long max(long v) {
#ifdef PERIADAPT_HAVE_MPI
  if (g_active) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_LONG, MPI_MAX, MPI_COMM_WORLD);
#endif
  return v;
}

double max_real(double v) {
#ifdef PERIADAPT_HAVE_MPI
  if (g_active) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
#endif
  return v;
}

void exchange_with(const std::vector<int>& peers, const std::vector<std::vector<double>>& send,
                   std::vector<std::vector<double>>& recv) {
#ifdef PERIADAPT_HAVE_MPI
  if (!g_active || peers.empty()) return;
  std::vector<MPI_Request> req(2 * peers.size());
  for (std::size_t k = 0; k < peers.size(); ++k)
    MPI_Irecv(recv[k].data(), static_cast<int>(recv[k].size()), MPI_DOUBLE, peers[k], 17,
              MPI_COMM_WORLD, &req[k]);
  for (std::size_t k = 0; k < peers.size(); ++k)
    MPI_Isend(send[k].data(), static_cast<int>(send[k].size()), MPI_DOUBLE, peers[k], 17,
              MPI_COMM_WORLD, &req[peers.size() + k]);
  MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE);
#else
  (void)peers;
  (void)send;
  (void)recv;
#endif
}

double sum_real(double v) {
#ifdef PERIADAPT_HAVE_MPI
  if (g_active) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
#endif
  return v;
}

void sum_exact(ExactSum* sums, std::size_t count) {
#ifdef PERIADAPT_HAVE_MPI
  if (!g_active || count == 0) return;
  constexpr std::size_t L = ExactSum::kLimbs;
  std::vector<std::int64_t> limbs(count * L);
  std::vector<double> special(count);
  for (std::size_t q = 0; q < count; ++q) {
    sums[q].normalize();
    std::copy(sums[q].limbs().begin(), sums[q].limbs().end(), limbs.begin() + static_cast<long>(q * L));
    special[q] = sums[q].special();
  }
  MPI_Allreduce(MPI_IN_PLACE, limbs.data(), static_cast<int>(limbs.size()), MPI_INT64_T, MPI_SUM,
                MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, special.data(), static_cast<int>(count), MPI_DOUBLE, MPI_SUM,
                MPI_COMM_WORLD);
  for (std::size_t q = 0; q < count; ++q) {
    std::copy(limbs.begin() + static_cast<long>(q * L), limbs.begin() + static_cast<long>((q + 1) * L),
              sums[q].limbs().begin());
    sums[q].special() = special[q];
    sums[q].normalize();
  }
#else
  (void)sums;
  (void)count;
#endif
}

template <class T>
void all_gather_into(const std::vector<T>& mine, std::vector<T>& out, std::vector<int>* counts) {
#ifdef PERIADAPT_HAVE_MPI
  if (g_active) {
    std::vector<int> n(static_cast<std::size_t>(g_size)), at(static_cast<std::size_t>(g_size));
    int own = static_cast<int>(mine.size());
    MPI_Allgather(&own, 1, MPI_INT, n.data(), 1, MPI_INT, MPI_COMM_WORLD);
    std::exclusive_scan(n.begin(), n.end(), at.begin(), 0);
    out.resize(static_cast<std::size_t>(at.back() + n.back()));
    MPI_Allgatherv(mine.data(), own, type_of<T>(), out.data(), n.data(), at.data(), type_of<T>(),
                   MPI_COMM_WORLD);
    if (counts) *counts = std::move(n);
    return;
  }
#endif
  if (counts) *counts = {static_cast<int>(mine.size())};
  out = mine;
}

template <class T>
std::vector<T> all_gather(const std::vector<T>& mine, std::vector<int>* counts) {
  std::vector<T> out;
  all_gather_into(mine, out, counts);
  return out;
}

template <class T>
std::vector<T> all_to_all(const std::vector<std::vector<T>>& send, std::vector<int>* counts) {
#ifdef PERIADAPT_HAVE_MPI
  if (g_active) {
    const auto P = static_cast<std::size_t>(g_size);
    std::vector<int> sn(P), sat(P), rn(P), rat(P);
    std::vector<T> flat;
    for (std::size_t r = 0; r < P; ++r) {
      sn[r] = static_cast<int>(send.at(r).size());
      flat.insert(flat.end(), send[r].begin(), send[r].end());
    }
    MPI_Alltoall(sn.data(), 1, MPI_INT, rn.data(), 1, MPI_INT, MPI_COMM_WORLD);
    std::exclusive_scan(sn.begin(), sn.end(), sat.begin(), 0);
    std::exclusive_scan(rn.begin(), rn.end(), rat.begin(), 0);
    std::vector<T> out(static_cast<std::size_t>(rat.back() + rn.back()));
    MPI_Alltoallv(flat.data(), sn.data(), sat.data(), type_of<T>(), out.data(), rn.data(),
                  rat.data(), type_of<T>(), MPI_COMM_WORLD);
    if (counts) *counts = std::move(rn);
    return out;
  }
#endif
  if (counts) *counts = {static_cast<int>(send.at(0).size())};
  return send.at(0);
}

template <class T>
std::vector<T> gather_to_root(const std::vector<T>& mine) {
#ifdef PERIADAPT_HAVE_MPI
  if (g_active) {
    std::vector<int> n(static_cast<std::size_t>(g_size)), at(static_cast<std::size_t>(g_size));
    int own = static_cast<int>(mine.size());
    MPI_Gather(&own, 1, MPI_INT, n.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::vector<T> out;
    if (g_rank == 0) {
      std::exclusive_scan(n.begin(), n.end(), at.begin(), 0);
      out.resize(static_cast<std::size_t>(at.back() + n.back()));
    }
    MPI_Gatherv(mine.data(), own, type_of<T>(), out.data(), n.data(), at.data(), type_of<T>(), 0,
                MPI_COMM_WORLD);
    return out;
  }
#endif
  return mine;
}

std::string first_text(const std::string& mine) {
  if (!distributed()) return mine;
  std::vector<int> counts;
  const std::vector<int> all = all_gather(std::vector<int>(mine.begin(), mine.end()), &counts);
  std::size_t at = 0;
  for (int c : counts) {
    if (c > 0) {
      std::string s(static_cast<std::size_t>(c), '\0');
      for (std::size_t k = 0; k < s.size(); ++k) s[k] = static_cast<char>(all[at + k]);
      return s;
    }
    at += static_cast<std::size_t>(c);
  }
  return {};
}

template void all_gather_into(const std::vector<double>&, std::vector<double>&, std::vector<int>*);
template std::vector<double> all_gather(const std::vector<double>&, std::vector<int>*);
template std::vector<std::uint32_t> all_gather(const std::vector<std::uint32_t>&, std::vector<int>*);
template std::vector<std::uint64_t> all_gather(const std::vector<std::uint64_t>&, std::vector<int>*);
template std::vector<int> all_gather(const std::vector<int>&, std::vector<int>*);
template std::vector<std::uint64_t> gather_to_root(const std::vector<std::uint64_t>&);
template std::vector<double> all_to_all(const std::vector<std::vector<double>>&, std::vector<int>*);
template std::vector<std::uint32_t> all_to_all(const std::vector<std::vector<std::uint32_t>>&,
                                               std::vector<int>*);
template std::vector<std::uint64_t> all_to_all(const std::vector<std::vector<std::uint64_t>>&,
                                               std::vector<int>*);

}  // namespace periadapt::mpi
