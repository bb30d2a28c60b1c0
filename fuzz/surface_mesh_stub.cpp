// The deck fuzzer exercises the YAML loader, not the CAD readers (CGAL, libgmsh), which have
// their own tests: in the fuzzer every surface or Gmsh file is refused as a deck error would be.
#include "discretize/surface_mesh.hpp"

namespace periadapt {

std::shared_ptr<const SolidSurface> load_solid_surface(const std::string& path) {
  throw SurfaceMeshError(path + ": surface files are not read in the deck fuzzer");
}

std::shared_ptr<const SolidSurface> load_gmsh_solid(const std::string& path, int) {
  throw SurfaceMeshError(path + ": Gmsh files are not read in the deck fuzzer");
}

}  // namespace periadapt
