#pragma once
// Linear least-squares fit of a nodal field around one node over its visible family: the
// neighbours joined to it by intact bonds. Used to interpolate u, v, a to new nodes (AGRS, thesis
// 3.2.4) and, as the PIM option of the refinement overlay, to virtual sub-grid points; because
// broken bonds are skipped, values never bridge a crack.
#include <array>
#include <cstdint>
#include <vector>

#include "core/bond_families.hpp"
#include "core/node_set.hpp"

namespace periadapt {

// G[c][a] = d F_c / d x_a at node p, from sum over visible j of (x_j - x_p)(F_j - F_p) and the
// moment matrix of the offsets; all zero when the visible family is degenerate (fewer than dim
// independent bonds), so the fit falls back to the node's own value. `beta`: the bond factors
// that decide visibility (default bf.beta; a copy when bf.beta is being changed concurrently).
void fit_gradient(const NodeSet& ns, const BondFamilies& bf, std::uint32_t p,
                  const std::array<std::vector<double>, 3>& F, double G[3][3],
                  const float* beta = nullptr);

}  // namespace periadapt
