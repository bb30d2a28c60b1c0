#pragma once
// Dual-horizon bond-based PMB (Ren et al. 2015; thesis 2.4, Eqs. 2.23-2.25, 3.1c): every family
// membership "j in H(i)" is a bond acting on BOTH ends with equal and opposite forces of
// magnitude c(delta_i)/2 g s beta_ij V_i V_j; node i collects the memberships of its own family
// and, through the transpose, those of the families that contain it (its dual horizon). Newton's
// third law holds for any mix of horizons, so refined grids have no ghost forces; on a uniform
// grid it equals the plain PMB. A membership breaks when its stretch exceeds its owner's s0.
#include <cstdint>
#include <vector>

#include "core/bond_families.hpp"
#include "core/node_set.hpp"
#include "material/dual_rows.hpp"
#include "material/micromodulus.hpp"

namespace periadapt {

// Needs bonds.t_* (build_transpose). Same contract as pmb_forces; `split`: a distributed
// pass's share (the breaks of its own rows only, applied and logged here).
std::size_t pmb_dual_forces(NodeSet& nodes, BondFamilies& bonds, InfluenceShape shape,
                            bool allow_breaking, std::vector<std::uint64_t>* broken_log,
                            std::vector<double>* W, const DualRows& split = {});

}  // namespace periadapt
