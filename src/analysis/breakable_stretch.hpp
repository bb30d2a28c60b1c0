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

// Per node: largest_breakable_stretch / critical stretch (1 = a bond is about to break), 0 where
// no bond can break; the VTU field `stretch_ratio`.
std::vector<double> breakable_stretch_ratio(const Model& m);

}  // namespace periadapt
