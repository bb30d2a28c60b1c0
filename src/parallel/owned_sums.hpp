#pragma once
// Sums over nodes that a distributed run takes without bringing every node up to date: each rank
// adds the nodes it owns (whose state it keeps current between syncs) into exact accumulators,
// and the ranks add their accumulators, so that the sum has the serial run's bits on any rank and
// thread count (core/exact_sum.hpp). A serial run adds every node.
#include <cstddef>

#include "core/exact_sum.hpp"
#include "parallel/row_partition.hpp"

namespace periadapt {

struct CountedNodes {
  const char* mine = nullptr;  // per node below `covered`: this rank adds it
  std::size_t covered = 0;
  bool beyond = true;          // whether this rank adds the nodes from `covered` on
  bool operator()(std::size_t i) const { return i < covered ? mine[i] != 0 : beyond; }
};

// The nodes this rank adds out of `n`: its own under an active partition `p` (null: serial).
// Nodes the partition has not seen yet (an event's children, which every rank computes alike)
// are rank 0's.
CountedNodes counted_nodes(const RowPartition* p, std::size_t n);

// Adds the ranks' accumulators (collective under an active partition; else nothing to do).
void add_over_ranks(const RowPartition* p, ExactSum* sums, std::size_t count);

}  // namespace periadapt
