#include "parallel/owned_sums.hpp"

#include "parallel/mpi_env.hpp"

namespace periadapt {

CountedNodes counted_nodes(const RowPartition* p, std::size_t n) {
  CountedNodes c;
  if (p == nullptr || !p->active) return c;
  if (p->mine.size() == n) {
    c.mine = p->mine.data();
  } else {
    c.none = mpi::rank() != 0;
  }
  return c;
}

void add_over_ranks(const RowPartition* p, ExactSum* sums, std::size_t count) {
  if (p != nullptr && p->active) mpi::sum_exact(sums, count);
}

}  // namespace periadapt
