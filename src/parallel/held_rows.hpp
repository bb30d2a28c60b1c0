#pragma once
// Held bond rows: in a distributed run, nothing but a rank's own force passes and refinement
// events read its bond arrays, so each rank keeps the rows its passes read (its own rows and
// those HeldReach adds) and frees the rest, the bulk of a model's memory (16 B per bond against
// about 270 B per node); an event gathers the rows it reads onto every rank first.
// The rows keep their contents and order, so a bond's name (BondFamilies::name: its row and its
// place there) is the same on every rank that holds its row; a checkpoint keeps each rank's own
// rows in a piece of its own (model/model_state.hpp), laid out by the whole model's row lengths
// (RowPartition::whole_offsets).
#include <cstdint>
#include <vector>

#include "core/bond_families.hpp"
#include "core/node_set.hpp"
#include "discretize/families.hpp"
#include "parallel/row_partition.hpp"

namespace periadapt {

// Which rows a rank holds besides its own: none (plain PMB and the history laws), those within
// two families of them (LPS: the neighbours' dilatations and their mutual-bond reach), or every
// row within the largest search radius (the dual-horizon pairing: the families that hold one of
// its nodes, whose memberships its nodes gather, and, being within that radius, its
// neighbours').
enum class HeldReach { Own, TwoFamilies, Radius };
HeldReach held_reach(bool state_based, bool dual_horizon);

// Keeps the rows `keep` (ascending) of whole arrays and empties the others, in contiguous
// arrays; records the whole model's row begins in `p` (rows_held). A dual-horizon transpose is
// made again over the kept rows (and the plain LPS pairing's far-end factors, which read `nodes`).
void hold_bond_rows(RowPartition& p, BondFamilies& bf, const std::vector<std::uint32_t>& keep,
                    const NodeSet& nodes);

// Refinement events with held rows (p.refining). An event reads and rebuilds the rows near its
// parents: `rows` (the same list on every rank) come from their owners to every rank that lacks
// them, so that every rank runs the event on the same rows, as a serial run does (collective).
void publish_rows(RowPartition& p, BondFamilies& bf, const std::vector<std::uint32_t>& rows);

// After an event (or, from whole arrays, at the first pass): the whole model's row lengths
// (every rank holds the rows the event rebuilt), owners for the new nodes (or a repartition),
// then each rank keeps its own rows and those `reach` adds, fetching what it lacks from the
// rows' previous owners (collective).
void rehold_rows(RowPartition& p, const NodeSet& ns, BondFamilies& bf, const QuadratureSpec& q,
                 HeldReach reach);

// Marks in `rows` (per node) the rows `reach` adds to the marked ones; rows flagged in `current`
// read their families from `bonds` (grow_by_families).
void grow_held_rows(const NodeSet& ns, const QuadratureSpec& q, std::vector<char>& rows,
                    HeldReach reach, const BondFamilies* bonds = nullptr,
                    const std::vector<char>* current = nullptr);

// A run that holds its rows from the start (no rank ever holds the whole arrays): splits the
// rows over the ranks by their sizes (the family search's count pass, storing no bond), then
// searches only this rank's rows and those `reach` adds. Fills `p` (active, owners, rows_held);
// collective.
BondFamilies build_held_families(RowPartition& p, const NodeSet& ns, const QuadratureSpec& q,
                                 HeldReach reach);

// After the set-up's per-row passes over held rows: every rank takes each row's damage weights
// from its owner, and the pre-crack count is the sum of the owners' cut entries (collective).
void share_held_setup(const RowPartition& p, NodeSet& ns, const BondFamilies& bf,
                      std::size_t& precrack_bonds);

// Each owner's values of its rows to every rank (collective): `v` (one value per node) holds
// this rank's own rows' values and leaves with every row's; with `rows` (the same list on every
// rank), those rows' only.
void share_owned_values(const RowPartition& p, std::vector<double>& v,
                        const std::vector<std::uint32_t>* rows = nullptr);
// The same for `stride` values per node (node i's at stride i ... stride i + stride - 1), every row.
void share_owned_values(const RowPartition& p, std::vector<double>& v, int stride);

// Row i's bond count in the whole model.
inline std::uint64_t whole_row_length(const RowPartition& p, const BondFamilies& bf, std::size_t i) {
  return p.rows_held ? p.whole_offsets[i + 1] - p.whole_offsets[i] : bf.end(i) - bf.begin(i);
}

// The bond count of the whole model (what a serial run reports).
std::uint64_t whole_bond_count(const RowPartition& p, const BondFamilies& bf);

}  // namespace periadapt
