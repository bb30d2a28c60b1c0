#include "parallel/owned_sums.hpp"

#include <algorithm>

#include "parallel/mpi_env.hpp"

namespace periadapt {

CountedNodes counted_nodes(const RowPartition* p, std::size_t n) {
  CountedNodes c;
  if (p == nullptr || !p->active) return c;
  c.mine = p->mine.data();
  c.covered = std::min(p->mine.size(), n);
  c.beyond = mpi::rank() == 0;
  return c;
}

void add_over_ranks(const RowPartition* p, ExactSum* sums, std::size_t count) {
  if (p != nullptr && p->active) mpi::sum_exact(sums, count);
}

}  // namespace periadapt
