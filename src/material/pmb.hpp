#pragma once
// Bond-based prototype microelastic brittle (PMB) model: force densities, bond breaking and
// strain-energy density. One kernel per dimension and influence shape, selected once per call.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/bond_families.hpp"
#include "core/node_set.hpp"
#include "material/blocks.hpp"
#include "material/micromodulus.hpp"
#include "overlay/pdro.hpp"

namespace periadapt {

struct PmbStepStats {
  std::size_t newly_broken = 0;
};

// Internal force density f_i = sum_j c_i g(xi/delta_i) s beta_j V_j e_ij for every active node,
// from the current positions y. When `allow_breaking`, bonds whose stretch exceeds the source
// node's critical stretch break irreversibly (unless either end is flagged no-fail).
// When `broken_log` is given, the indices of the bonds broken by this call are appended to it
// (in no particular order) so that a step can be undone. When `W` is given, it receives the
// strain-energy density of every node from the same pass (inactive nodes: 0).
// `pdro`: bonds about to break are re-checked by the refinement overlay (overlay/pdro.hpp).
// `thermal_strain` = alpha dT enters every bond stretch as s - alpha dT (Stewart & Jeon Eq. 13).
// `rows`: only these nodes' forces (and, when W is given, energy densities) are computed; the
// others keep theirs.
// `breakable_stretch`: also the largest stretch of each computed row's intact breakable bonds
// (the stretch trigger's measure, from the same sweep; -inf for a row without such a bond).
// `pairs`: several materials (material/blocks.hpp): each bond's micromodulus and critical stretch
// by the blocks of its two ends; stretches (breakable_stretch too) in units of s0_i / s0_ij.
PmbStepStats pmb_forces(NodeSet& nodes, BondFamilies& bonds, InfluenceShape shape,
                        bool allow_breaking, std::vector<std::uint64_t>* broken_log = nullptr,
                        std::vector<double>* W = nullptr, const PdroSpec* pdro = nullptr,
                        double thermal_strain = 0.0,
                        const std::vector<std::uint32_t>* rows = nullptr,
                        std::vector<double>* breakable_stretch = nullptr,
                        const BlockPairs* pairs = nullptr);

// Strain-energy density W_i = 1/4 sum_j c_i g s^2 xi beta_j V_j over intact bonds (thesis 2.14).
// `rows`: only these nodes' densities are computed; the others keep theirs.
void pmb_energy_density(const NodeSet& nodes, const BondFamilies& bonds, InfluenceShape shape,
                        std::vector<double>& W, double thermal_strain = 0.0,
                        const std::vector<std::uint32_t>* rows = nullptr,
                        const BlockPairs* pairs = nullptr);

// sum_j c_i g beta_j V_j / xi: the stiffness sum of the Silling-Askari stable-step bound.
void pmb_stiffness_sum(const NodeSet& nodes, const BondFamilies& bonds, InfluenceShape shape,
                       std::vector<double>& K, const BlockPairs* pairs = nullptr);
// The same sum for one node.
double pmb_stiffness_row(const NodeSet& nodes, const BondFamilies& bonds, InfluenceShape shape,
                         std::size_t i, const BlockPairs* pairs = nullptr);

// Stress of every node, sigma_i = dW_i / d(eps) for the energy density above:
// 1/2 sum_j c_i g s beta_j V_j e_ij (x) xi_ij over intact bonds (the bond-based stress; the
// classical stress of a homogeneous strain where W_i is classical). Row-major 3 x 3 per node.
void pmb_stress(const NodeSet& nodes, const BondFamilies& bonds, InfluenceShape shape,
                std::vector<double>& sigma, double thermal_strain = 0.0,
                const BlockPairs* pairs = nullptr);

}  // namespace periadapt
