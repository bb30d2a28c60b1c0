#pragma once
// Distributed runs (mpirun -np N): every rank holds the whole node set, and each bond row's forces
// are computed on one rank only, its owner; the owners then share what they computed (forces,
// broken bonds, broken weights, energy densities when asked), so that every rank ends each force
// pass in the state a serial pass gives, bit for bit. The rows are split by Zoltan's recursive
// coordinate bisection or Hilbert space-filling curve over the node positions, weighted by each
// row's bond count. When refinement adds nodes, children join their parent's rank; once the
// largest rank's bonds pass the mean by more than the deck's threshold, Zoltan repartitions
// starting from the current owners (LB_APPROACH REPARTITION, which keeps moves few). Every rank
// holds the whole node set, so a move hands over the node's ownership and, where each rank keeps
// only the bond rows its passes read (parallel/held_rows.hpp), the row's bonds. Refinement events
// and observers run on every rank alike on the same data (an event on the rows gathered for it);
// rank 0 writes the files. The explicit solver integrates each rank's region only where it can
// (parallel/ghost_layer.hpp) and brings the rest up to date before anything reads it.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/bond_families.hpp"
#include "core/node_set.hpp"

namespace periadapt {

enum class PartitionMethod { Rcb, Hsfc };

struct RowPartition {
  bool active = false;
  PartitionMethod method = PartitionMethod::Rcb;
  std::vector<std::uint32_t> owned;  // this rank's rows, ascending
  std::vector<char> mine;            // per node: owned here
  std::vector<std::uint32_t> all_owned;  // every rank's owned rows, concatenated in rank order
  std::vector<int> owner;            // per node: its rank
  std::size_t nodes = 0;             // the node count it was made for
  std::size_t bonds = 0;             // the bond count it was made for
  double rebalance_threshold = 0.10;  // repartition when imbalance exceeds 1 + this
  double imbalance = 1.0;            // largest rank's work over the mean
  // Multi-rate stepping: each node's step in units of dt (its row's work per step is its bonds
  // over it), identical on every rank; empty, or a node beyond it: every step.
  std::vector<std::uint8_t> rates;
  long partitions = 0;               // how many times Zoltan made it (the first split included)
  long extensions = 0;               // refinement events absorbed without a repartition
  long generation = 0;               // counts the owner assignments
  // This rank's rows and the rows around them, for the owner assignment `around_generation`
  // and the kind `around_transpose` (rows_around).
  std::vector<std::uint32_t> around;
  long around_generation = -1;
  bool around_transpose = false;
  // Owned integration (parallel/ghost_layer.hpp): the explicit solver advances this rank's
  // region only, and a pass with ghost_pass set shares the exported forces alone.
  bool ghost_mode = false;
  bool ghost_pass = false;
  std::vector<std::uint32_t> region;        // ascending
  std::vector<char> in_region;              // per node
  // The ranks this one exchanges ghost forces with; per peer, the owned nodes in its region
  // (sent) and the peer's nodes in this rank's region (received), ascending.
  std::vector<int> peers;
  std::vector<std::vector<std::uint32_t>> send_ids, recv_ids;
  std::size_t ghosts = 0;  // nodes of this rank's region it does not own
  long region_generation = -1;
  long region_steps = 0;  // steps that integrated the region alone
  // Refinement events that brought only their window up to date, and those of them whose
  // repartition then had the previous owners send everything.
  long window_events = 0, window_events_resynced = 0;
  // Held bond rows (parallel/held_rows.hpp): this rank's bond arrays hold the rows its passes
  // read and no others (rows_held), searched so at set-up or, in a run that asks for them
  // (hold_rows) after reading whole arrays (a restart), kept so by its first pass; the whole
  // model's rows begin at whole_offsets (a checkpoint's layout).
  bool hold_rows = false;
  bool rows_held = false;
  // Refinement events change the rows (adaptive runs): each event gathers the rows it reads onto
  // every rank first, and the ranks hold their rows afresh after it (rehold_rows).
  bool refining = false;
  std::vector<char> held;  // per node: this rank has the row's contents (while rows_held)
  std::vector<std::uint64_t> whole_offsets;
  std::uint64_t whole_capacity = 0;  // the whole arrays' room (a checkpoint records it)
  std::size_t held_row_count = 0;
};

// When the partition is active and the nodes or bonds changed since the last call: the first
// call splits the rows, later ones give new nodes their parent's rank and repartition when the
// imbalance passes the threshold (collective: every rank calls it at the same point). A row's
// work is its bonds per step: its bonds over its multi-rate step (`rates`).
void refresh_partition(RowPartition& p, const NodeSet& ns, const BondFamilies& bf);

// This rank's rows and the rows around them, ascending, kept until the owners change: with
// `transpose`, the owners of the families that contain one of its nodes (bonds.t_*: whose
// memberships a dual-horizon pass evaluates); otherwise its rows' neighbours (whose LPS
// dilatations its forces read).
const std::vector<std::uint32_t>& rows_around(RowPartition& p, const BondFamilies& bf, bool transpose);

// This rank's share of `rows` (all rows when null).
std::vector<std::uint32_t> owned_rows(const RowPartition& p, const std::vector<std::uint32_t>* rows);

// After each rank computed the forces of its `rows`: every rank receives every computed row's
// force and, where any rank asks for them, energy density W and breakable stretch; applies the
// bonds the other ranks broke (beta, and the broken weights of their rows as the owners summed
// them); and
// appends to `log` every bond broken on any rank. Returns how many broke in all (collective).
// `rows` == p.owned (a full pass) travels without its ids: every rank knows the partition.
std::size_t share_force_pass(const RowPartition& p, NodeSet& ns, BondFamilies& bf,
                             const std::vector<std::uint32_t>& rows,
                             const std::vector<std::uint64_t>& broken_here,
                             std::vector<std::uint64_t>* log, std::vector<double>* W,
                             std::vector<double>* stretch);

}  // namespace periadapt
