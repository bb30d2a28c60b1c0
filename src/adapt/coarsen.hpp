#pragma once
// Coarsening (Bobaru et al. 2009, Algorithm 1): a refined parent whose children are all active,
// unrefined and undamaged returns to the grid; its children are deactivated. The parent takes
// the children's mass-weighted mean displacement, velocity and acceleration (linear momentum is
// kept exactly) and its own horizon, micromodulus and critical stretch back.
#include <cstdint>
#include <vector>

#include "adapt/adapt_spec.hpp"
#include "adapt/refine.hpp"
#include "model/model.hpp"

namespace periadapt {

// Parents whose children are all active leaves without broken bonds (pre-crack bonds aside).
std::vector<std::uint32_t> coarsenable_parents(const Model& m);

RefineStats coarsen_nodes(Model& m, const std::vector<std::uint32_t>& parents);

}  // namespace periadapt
