#pragma once
// Neighbor search: full CSR bond families H(i) = { j : |x_j - x_i| <= delta_i } built with a cell
// list in O(N), in parallel, with the partial-volume factor of each bond.
#include "core/bond_families.hpp"
#include "core/node_set.hpp"
#include "discretize/partial_volume.hpp"

namespace periadapt {

struct QuadratureSpec {
  Quadrature rule = Quadrature::PaPdlammps;
  double lattice_rotation = 0.0;  // radians; orientation of the (2D) cells for sub-cell sampling
};

// With `keep` and `rebuild`: rows of nodes not flagged in `rebuild` (and existing in `keep`) are
// copied from `keep` as they are (bond states included), only flagged rows are searched again.
BondFamilies build_families(const NodeSet& nodes, const QuadratureSpec& quadrature,
                            const BondFamilies* keep = nullptr,
                            const std::vector<char>* rebuild = nullptr);

// The same into `out` (not `keep`), reusing its storage: refinement events build into a spare
// set of arrays instead of fresh ones, whose first touch (page faults, zero fill) cost about as
// much as the rebuild itself on large models.
void build_families_into(BondFamilies& out, const NodeSet& nodes, const QuadratureSpec& quadrature,
                         const BondFamilies* keep = nullptr,
                         const std::vector<char>* rebuild = nullptr);

// Builds the transpose of the families (t_offsets, t_owner, t_bond), sorted by owner.
void build_transpose(BondFamilies& bonds);

// Bonds with an end on a no-fail node can never break (flag carried by the bond's sign).
// `rows` (optional): only the rows of flagged nodes (the others are known to be up to date).
void mark_unbreakable_bonds(const NodeSet& nodes, BondFamilies& bonds,
                            const std::vector<char>* rows = nullptr);

// Recomputes the damage denominators (sum of beta*V_j over each family) and numerators.
void update_damage_weights(NodeSet& nodes, const BondFamilies& bonds,
                           const std::vector<char>* rows = nullptr);

}  // namespace periadapt
