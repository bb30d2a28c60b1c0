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

// Where refinement puts new nodes in a cell: method B at the sub-cell centres, method A on the
// lattice of half the spacing through the node (cell edges included); turned by the 2D grid's
// rotation (radians).
struct ChildLattice {
  bool method_a = false;
  double rotation = 0.0;
};

// Points lying on crack c (within 1e-9 of their spacing of its line or plane, strictly inside
// its extent): a node there is on neither side, keeps its bonds to both faces and bridges the
// crack. The active nodes, and with `levels` > 0 the points refinement (`lattice`) would put in
// their cells at levels 1 ... levels. Counts the points of the lowest level that has any;
// `level` and `first` receive that level and its first point.
std::size_t points_on_precrack(const NodeSet& nodes, const PreCrack& c, int levels,
                               const ChildLattice& lattice, int* level, Vec3* first);

}  // namespace periadapt
