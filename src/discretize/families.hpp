#pragma once
// Neighbor search: full CSR bond families H(i) = { j : |x_j - x_i| <= delta_i } built with a cell
// list in O(N), in parallel, with the partial-volume factor of each bond.
#include <vector>

#include "core/bond_families.hpp"
#include "core/node_set.hpp"
#include "discretize/partial_volume.hpp"

namespace periadapt {

struct QuadratureSpec {
  Quadrature rule = Quadrature::PaPdlammps;
  double lattice_rotation = 0.0;  // radians; orientation of the (2D) cells for sub-cell sampling
};

// Spare bond capacity (fraction of the bonds) that refinement keeps for the rows it appends.
inline constexpr double kRefinementBondHeadroom = 0.25;

// The families of every active node, rows contiguous in node order. `headroom`: spare capacity
// (a fraction of the bonds) reserved for rows that refinement will append; it is address space
// only until used (pages untouched), so it costs no resident memory.
// `rows` (optional): only the flagged nodes' rows are searched; the others stay empty.
BondFamilies build_families(const NodeSet& nodes, const QuadratureSpec& quadrature,
                            double headroom = 0.0, const std::vector<char>* rows = nullptr);

// Adds to `rows` (per node) every family member of its rows, `layers` times over, storing no
// bond (the rows a distributed LPS rank holds around its own: parallel/held_rows.hpp). Rows
// flagged in `current` read their members from `bonds` (their lists must be what a search
// gives now); the others are searched.
void grow_by_families(const NodeSet& nodes, const QuadratureSpec& quadrature,
                      std::vector<char>& rows, int layers, const BondFamilies* bonds = nullptr,
                      const std::vector<char>* current = nullptr);

// The row begins build_families would give (its count pass; `rows` as there), with no bond
// stored: what splitting the rows over ranks by their work needs before any rank searches them.
std::vector<std::uint64_t> family_offsets(const NodeSet& nodes, const QuadratureSpec& quadrature,
                                          const std::vector<char>* rows = nullptr);

// Searches again the rows of the flagged nodes (and gives nodes appended since the last build
// empty rows first): each such row is written after the current arrays, whose old entries turn
// into slack; the other rows are not touched, so the cost follows the flagged rows. When the
// slack exceeds a quarter of the live bonds, the arrays are compacted once (rows in node order).
// Bond indices change: nothing may hold one across the call. Transposes are cleared.
// `patch` (optional): flagged rows whose old family is still right except that some neighbours
// were switched off and nodes were appended (ids from the old row count on); such a row keeps
// its entries for the active old neighbours (bond states included) and only the appended nodes
// are searched. The result equals the searched row's; switching a node's spacing or horizon off
// this path (method A parents, interface horizons) needs a full search of the rows that see it.
void rebuild_rows(BondFamilies& bonds, const NodeSet& nodes, const QuadratureSpec& quadrature,
                  const std::vector<char>& rows, const std::vector<char>* patch = nullptr);

// What a search of the rows `rows` would write, without touching the families: per row, its
// entries sorted by neighbour. A surface correction that updates a window of rows reads the
// uncorrected factors of the rows around it this way.
struct QuadratureEntry {
  std::uint32_t j;
  float beta;
  double inv_length;
};
std::vector<std::vector<QuadratureEntry>> quadrature_factors(
    const NodeSet& nodes, const QuadratureSpec& quadrature, const std::vector<std::uint32_t>& rows);

// Active nodes (ascending ids) inside the bounding box of `seeds` grown by `margin`: the
// candidates of a local search, found by one pass over the coordinates.
std::vector<std::uint32_t> active_nodes_near(const NodeSet& nodes,
                                             const std::vector<std::uint32_t>& seeds, double margin);

// Active nodes (ascending ids) within `radius` of one of `seeds`, and the seeds themselves
// (active or not): the rows an event's change can reach.
std::vector<std::uint32_t> nodes_within(const NodeSet& nodes, const std::vector<std::uint32_t>& seeds,
                                        double radius);

// Builds the transpose of the families (t_offsets, t_owner, t_bond), sorted by owner.
void build_transpose(BondFamilies& bonds);

// Builds reverse_at and reverse_beta: each row's far-end quadrature factors, kept for the rows
// where one differs from the row's own (BondFamilies). Only rows with a far end of another
// horizon or cell size are searched: between equal cells and horizons the factors agree.
// `redo`: only these rows are made again; the others keep theirs (their rows and their far
// ends' rows unchanged since, wherever they now lie).
void build_reverse(BondFamilies& bonds, const NodeSet& nodes,
                   const std::vector<char>* redo = nullptr);

// What a force form reads of the other ends' rows, made again after rows were built or moved
// and their factors corrected: the dual-horizon transpose, or the plain LPS pairing's far-end
// factors where the active nodes have more than one horizon. `changed`: the rows an event
// searched again or whose factors it corrected (every row that reaches a changed node is among
// them); the far-end factors of the other rows not bonded to one are kept. `member_reach` (with
// `changed`): no member lies farther than this from its row, so only rows that near a changed
// one are looked at; 0: every row is.
void index_pairs(BondFamilies& bonds, const NodeSet& nodes, bool dual_horizon, bool state_based,
                 const std::vector<char>* changed = nullptr, double member_reach = 0);

// Bonds with an end on a no-fail node can never break (flag carried by the bond's sign).
// `rows` (optional): only the rows of flagged nodes (the others are known to be up to date).
void mark_unbreakable_bonds(const NodeSet& nodes, BondFamilies& bonds,
                            const std::vector<char>* rows = nullptr);

// Recomputes the damage denominators (sum of beta*V_j over each family) and numerators.
void update_damage_weights(NodeSet& nodes, const BondFamilies& bonds,
                           const std::vector<char>* rows = nullptr);

}  // namespace periadapt
