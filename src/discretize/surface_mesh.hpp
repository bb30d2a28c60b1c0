#pragma once
// Solids bounded by a closed triangulated surface from a CAD file (STL, OFF, OBJ, PLY; CGAL's
// readers), for bodies, holes and regions: `surface: part.stl`. The inside test is exact
// (CGAL's Side_of_triangle_mesh with exact predicates), so lattice cells are kept by their
// centres as for the other shapes.
#include <memory>
#include <stdexcept>
#include <string>

#include "core/geometry.hpp"

namespace periadapt {

struct SurfaceMeshError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reads and checks the surface (triangulated if needed; it must be closed and bound a volume);
// throws SurfaceMeshError naming the file and the problem.
std::shared_ptr<const SolidSurface> load_solid_surface(const std::string& path);

}  // namespace periadapt
