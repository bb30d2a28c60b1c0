#pragma once
// Solids bounded by a closed triangulated surface from a CAD file (STL, OFF, OBJ, PLY; CGAL's
// readers) or covered by a Gmsh mesh, for bodies, holes and regions: `surface: part.stl`,
// `gmsh: plate.msh`. The inside test is exact
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

// The region a Gmsh mesh or geometry (.msh, .geo, ...) covers, read with libgmsh: its linear
// triangles (2D, as a prism about z = 0 for the inside test) or tetrahedra (3D), meshed first
// when the file has none. Throws SurfaceMeshError.
std::shared_ptr<const SolidSurface> load_gmsh_solid(const std::string& path, int dim);

}  // namespace periadapt
