#pragma once
// Several materials in one body (deck list `blocks`). Every node carries its block's law: its
// micromodulus, critical stretch and density, scaled with its horizon as any node's are. A bond
// between blocks a and b
// - PMB: has the micromodulus of the harmonic mean of the two moduli, 2 E_a E_b / (E_a + E_b),
//   at the source node's horizon, so the two ends of one bond pull equally where their horizons
//   agree, as within one block (the source node's own c_i would not: a wave crossing the joint
//   would see unequal and opposite forces);
// - LPS: each end's force state uses its own block's moduli; the pair t_ij + t_ji is equal and
//   opposite by construction;
// - fails at the critical stretch of the smaller fracture energy with the harmonic-mean moduli
//   (the weaker material sets the joint's toughness), or at the smaller critical stretch where a
//   block gives one directly.
// The kernels read two factors per bond from tables indexed by the two ends' blocks; within a
// block both are exactly 1, so a deck whose blocks repeat one material runs as without them (to
// round-off: the block kernels order their vector sums differently).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "material/material_law.hpp"

namespace periadapt {

struct BlockPairs {
  std::size_t count = 0;  // blocks; below 2 the tables are empty and nodes carry no block id
  // [a * count + b], for a bond from a node of block a to one of block b:
  std::vector<double> stiffness;    // factor on the source node's micromodulus
  std::vector<double> inv_stretch;  // s0_a / s0_ab: the bond breaks when s * this > s0_i
  bool active() const { return count > 1; }
  const double* stiffness_row(std::uint8_t a) const { return stiffness.data() + a * count; }
  const double* inv_stretch_row(std::uint8_t a) const { return inv_stretch.data() + a * count; }
};

// The pair tables of `laws` (one per block) for a model of dimension `dim` at horizon `delta`.
// `state_based`: critical stretches by the LPS formula.
BlockPairs block_pair_rules(const std::vector<MaterialLaw>& laws, int dim, bool state_based,
                            double delta);

}  // namespace periadapt
