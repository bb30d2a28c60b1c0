#include "discretize/surface_mesh.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
#include <filesystem>

namespace periadapt {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
namespace PMP = CGAL::Polygon_mesh_processing;

class CgalSolid final : public SolidSurface {
 public:
  explicit CgalSolid(Mesh m) : mesh_(std::move(m)) {
    tree_ = std::make_unique<Tree>(faces(mesh_).first, faces(mesh_).second, mesh_);
    tree_->accelerate_distance_queries();
    side_ = std::make_unique<CGAL::Side_of_triangle_mesh<Mesh, Kernel>>(*tree_);
    const CGAL::Bbox_3 b = PMP::bbox(mesh_);
    bounds_.lo = {b.xmin(), b.ymin(), b.zmin()};
    bounds_.hi = {b.xmax(), b.ymax(), b.zmax()};
    volume_ = std::abs(PMP::volume(mesh_));
  }
  bool inside(const Vec3& p) const override {
    return (*side_)(Point(p[0], p[1], p[2])) != CGAL::ON_UNBOUNDED_SIDE;
  }
  double distance(const Vec3& p) const override {
    return std::sqrt(tree_->squared_distance(Point(p[0], p[1], p[2])));
  }
  Box bounds() const override { return bounds_; }
  double volume() const override { return volume_; }

 private:
  Mesh mesh_;
  std::unique_ptr<Tree> tree_;
  std::unique_ptr<CGAL::Side_of_triangle_mesh<Mesh, Kernel>> side_;
  Box bounds_;
  double volume_ = 0;
};

}  // namespace

std::shared_ptr<const SolidSurface> load_solid_surface(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw SurfaceMeshError(path + ": cannot open the surface file (not a regular file)");
  Mesh mesh;
  if (!PMP::IO::read_polygon_mesh(path, mesh) || mesh.is_empty())
    throw SurfaceMeshError(path + ": not a readable surface mesh (STL, OFF, OBJ or PLY with "
                                  "faces that form a polygon mesh)");
  if (!CGAL::is_triangle_mesh(mesh)) PMP::triangulate_faces(mesh);
  if (!CGAL::is_closed(mesh))
    throw SurfaceMeshError(path + ": the surface is not closed (it has border edges); a body "
                                  "needs a watertight surface");
  if (!(std::abs(PMP::volume(mesh)) > 0))
    throw SurfaceMeshError(path + ": the surface encloses no volume");
  return std::make_shared<CgalSolid>(std::move(mesh));
}

}  // namespace periadapt
