#pragma once
// adapt.fill_boundary_cells (method B): a parent splits into the sub-cells of its own cell, but
// where a hole, a clipped body or a rotated lattice cuts the grid, a neighbouring cell whose
// centre lies outside the body has no node although some of its sub-cells lie inside, where the
// uniform fine grid has nodes. Without them a refined zone keeps the coarse grid's staircase,
// whose steps its fine nodes resolve as re-entrant corners (docs/agrs.md, "Refined zones at
// curved boundaries"). These are the fillers of such cells.
#include <array>
#include <cstdint>
#include <vector>

#include "adapt/adapt_spec.hpp"
#include "adapt/crack_memory.hpp"
#include "model/model.hpp"

namespace periadapt {

// The offset of lattice cell k (in cells of spacing h) from a node, along the (2D: rotated)
// lattice axes; and the offset of sub-cell c (bit d: + or - h/4 along axis d).
Vec3 lattice_offset(const Model& m, const int k[3], double h);
std::array<double, 3> sub_cell_offset(const Model& m, int c, double h);

struct BoundaryFiller {
  std::uint32_t parent;  // the event's parent it joins (its children's list, for coarsening)
  Vec3 pos;
  double u[3], v[3], a[3];
};

struct BoundaryFill {
  std::vector<BoundaryFiller> fillers;  // in the order of `parents`
  std::vector<char> boundary_parent;    // per node: a parent with an empty cell next to it
};

// The fillers an event with these parents makes (none without spec.fill_boundary_cells or a
// boundary that cuts the lattice). An empty cell is filled once every cell around it with a node
// is refined (earlier, a filler beside a coarse cell would step the surface where the zone
// ends); a filler takes the mean extrapolation of the nearest nodes that see it, so that
// mirror-image fillers get mirror-image fields whichever parent makes them. Parents with loads
// or prescribed motions fill nothing (their regions' resultants stay exact). Reads the grid as
// it was before the event (parents still active).
BoundaryFill boundary_fillers(const Model& m, const AdaptSpec& spec, const CrackMemory& memory,
                              const std::vector<std::uint32_t>& parents,
                              const std::vector<char>& is_parent);

}  // namespace periadapt
