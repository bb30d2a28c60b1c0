#pragma once
// Owned integration in distributed explicit runs. Each rank advances only the nodes its force
// pass reads (its region: its rows, the rows whose dilatations or dual memberships it evaluates,
// and their neighbours; each rank sums the external work of its own loaded and driven nodes),
// and after each pass receives from their owners the forces of the region's nodes it does not
// own. The nodes outside its region go stale; a sync gathers every node's state from its owner
// whenever something reads the whole model (checkpoints, the end of the run, events that
// repartition or read beyond their window), so that every rank then holds what the serial run
// holds, bit for bit. The outputs sum each rank's own nodes exactly (parallel/owned_sums.hpp).
#include <cstdint>
#include <vector>

#include "core/bond_families.hpp"
#include "core/node_set.hpp"
#include "parallel/row_partition.hpp"

namespace periadapt {

// Rebuilds p.region, p.in_region and the peers' send and receive lists for the current owners
// when they changed (collective). `around`: the rows whose neighbours' positions the pass reads
// (its rows, and the rows of the LPS dilatations or dual memberships it evaluates).
void refresh_ghost_layer(RowPartition& p, const BondFamilies& bf,
                         const std::vector<std::uint32_t>& around);

// After a pass: each rank sends its peers the forces of its nodes in their regions, and receives
// its ghosts' forces from their owners (point to point; every rank calls it).
void share_ghost_forces(const RowPartition& p, NodeSet& ns);

// Every rank's owned u, v, a, f (and `per_row`: per-node fields each owner holds for its rows;
// the same list on every rank) to all, and the current positions from them (collective).
void gather_owned_state(const RowPartition& p, NodeSet& ns,
                        const std::vector<std::vector<double>*>& per_row);

// The nodes of every rank's region whose u or v differ from their owner's, summed over the
// ranks (collective): zero whenever the regions are current. A diagnostic (an event's window
// sync must leave none; tests/cli_mpi.sh checks it under PERIADAPT_CHECK_REGIONS).
long stale_region_nodes(const RowPartition& p, const NodeSet& ns);

}  // namespace periadapt
