#pragma once
// Pre-cracks: every bond crossing a segment (2D) or a planar quadrilateral (3D) is broken before
// the run starts (the bond keeps its slot, marked broken, so it counts as initial damage).
#include <array>
#include <vector>

#include "core/bond_families.hpp"
#include "core/geometry.hpp"
#include "core/node_set.hpp"

namespace periadapt {

struct PreCrack {
  bool planar3d = false;       // false: segment a-b in the xy-plane; true: quadrilateral
  std::array<Vec3, 4> points;  // segment uses points[0], points[1]
};

// Breaks the crossing bonds; returns the number of directed bond entries broken. `rows`
// (optional): only the rows of flagged nodes (a refinement event's rebuilt rows; the others keep
// their cut bonds). `per_crack` (optional) receives each crack's count of the bonds it broke.
std::size_t apply_precracks(const NodeSet& nodes, BondFamilies& bonds,
                            const std::vector<PreCrack>& cracks,
                            const std::vector<char>* rows = nullptr,
                            std::vector<std::size_t>* per_crack = nullptr);

}  // namespace periadapt
