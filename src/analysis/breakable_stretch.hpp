#pragma once
// How near each bond family is to breaking: the largest stretch of a row's intact, breakable
// bonds. With several materials each bond counts in units of s0_i / s0_ij (material/blocks.hpp),
// so the value compares with the row's own critical stretch either way. -inf for a row with no
// such bond (no-fail nodes, rows fully broken).
#include <cstdint>
#include <vector>

#include "model/model.hpp"

namespace periadapt {

double largest_breakable_stretch(const Model& m, std::uint32_t i);

// The same over the bonds to nodes of the row's own level or coarser: the stretch trigger's
// measure. A coarse row's bonds into a finer zone stretch with the zone's own field and its
// interface forces, which the coarse grid does not have; counted, they flag the zone's coarse
// neighbours and the zone grows by a horizon at a time (docs/agrs.md, "Bonds into a finer zone").
double largest_breakable_stretch_own_level(const Model& m, std::uint32_t i);

// Per node: largest_breakable_stretch / critical stretch (1 = a bond is about to break), 0 where
// no bond can break; the VTU field `stretch_ratio`.
std::vector<double> breakable_stretch_ratio(const Model& m);

}  // namespace periadapt
