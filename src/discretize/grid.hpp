#pragma once
// Uniform particle grids in 1D (bar), 2D (rectangle with thickness) and 3D (box), optionally
// rotated (2D) and clipped to the body, with holes removed.
#include <array>
#include <optional>
#include <vector>

#include "core/geometry.hpp"
#include "core/node_set.hpp"

namespace periadapt {

enum class Registration { CellCentered, NodeOnEdge };

struct GridSpec {
  int dim = 2;
  double spacing = 1e-3;
  Box body;                      // the body (only the first dim components are used)
  double thickness = 1.0;        // 2D thickness (m), or 1D cross-section area (m^2)
  double rotation_deg = 0.0;     // 2D only: lattice angle about `pivot`
  Vec3 pivot{0, 0, 0};           // rotation centre (default: body centre, set by the caller)
  Registration registration = Registration::CellCentered;
  std::vector<Shape> holes;
  std::optional<Shape> clip;     // a body that is not a box (2D disk): nodes outside are dropped
  // A point-cloud body: these nodes (x, y, z, volume) in this order instead of the lattice's;
  // `body` is then their cells' bounding box.
  std::vector<std::array<double, 4>> points;
};

// Appends the grid's nodes to `nodes` (volume = cell measure times thickness/area) and returns
// how many were added. `removed_by_hole` (optional): per hole, the grid points inside the body
// that it removed (a point inside several holes counts for the first).
std::size_t generate_grid(const GridSpec& spec, NodeSet& nodes,
                          std::vector<std::size_t>* removed_by_hole = nullptr);

// Cell measure of one node: dx (1D, times area), dx^2 t (2D), dx^3 (3D).
double cell_volume(int dim, double dx, double thickness);

}  // namespace periadapt
