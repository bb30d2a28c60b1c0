#pragma once
// How well the refined zone covers the cracks (thesis 6.2, Fig. 6.11): an energy trigger alone
// refines regions "not interested by cracks" and misses where cracks grow. Counts the active
// refined nodes farther than `radius` from every cracked node, and the cracked nodes left on
// the coarse grid.
#include <cstddef>

#include "core/node_set.hpp"

namespace periadapt {

struct RefinementCoverage {
  std::size_t refined = 0;                // active nodes with level > 0
  std::size_t refined_far_from_cracks = 0;
  std::size_t cracked = 0;                // active nodes with damage above the threshold
  std::size_t cracked_coarse = 0;         // of those, on level 0
};

RefinementCoverage refinement_coverage(const NodeSet& nodes, double damage_threshold,
                                       double radius);

}  // namespace periadapt
