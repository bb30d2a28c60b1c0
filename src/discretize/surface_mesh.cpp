#include "discretize/surface_mesh.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <vector>

#include "discretize/gmsh_library.hpp"

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

// Overlapping or crossing parts make the inside test count crossings of both: their common
// volume would come out empty (an exclusive or, not a union).
void refuse_self_intersection(const std::string& path, const Mesh& mesh) {
  if (PMP::does_self_intersect(mesh))
    throw SurfaceMeshError(path + ": the surface intersects itself (overlapping or crossing "
                                  "parts); merge them into one closed surface");
}

// The closed surface of a triangle soup, oriented and checked.
std::shared_ptr<const SolidSurface> solid_from_soup(const std::string& path,
                                                    std::vector<Point> points,
                                                    std::vector<std::array<std::size_t, 3>> faces) {
  PMP::orient_polygon_soup(points, faces);
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, faces, mesh);
  if (mesh.is_empty() || !CGAL::is_closed(mesh))
    throw SurfaceMeshError(path + ": the mesh's boundary is not closed");
  refuse_self_intersection(path, mesh);
  if (!(std::abs(PMP::volume(mesh)) > 0)) throw SurfaceMeshError(path + ": the mesh has no volume");
  return std::make_shared<CgalSolid>(std::move(mesh));
}

}  // namespace

std::shared_ptr<const SolidSurface> load_gmsh_solid(const std::string& path, int dim) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw SurfaceMeshError(path + ": cannot open the Gmsh file (not a regular file)");
  // Linear triangles (2D) or tetrahedra (3D); a geometry without a mesh is meshed first.
  const int corners = dim == 2 ? 3 : 4;
  GmshMesh mesh;
  try {
    mesh = read_gmsh_mesh(path, dim);
  } catch (const std::exception& e) {
    throw SurfaceMeshError(path + ": Gmsh could not read it: " + e.what());
  }
  const std::vector<std::size_t>& element_tags = mesh.element_tags;
  const std::vector<std::size_t>& element_nodes = mesh.element_nodes;
  const std::vector<std::size_t>& node_tags = mesh.node_tags;
  const std::vector<double>& coords = mesh.coords;
  if (element_nodes.size() != static_cast<std::size_t>(corners) * element_tags.size() ||
      coords.size() != 3 * node_tags.size())
    throw SurfaceMeshError(path + ": Gmsh gave an inconsistent mesh");
  if (element_tags.empty())
    throw SurfaceMeshError(path + (dim == 2 ? ": no triangles (2D models need a surface mesh)"
                                            : ": no tetrahedra (3D models need a volume mesh)"));
  std::map<std::size_t, std::size_t> index;
  std::vector<Point> points;
  for (std::size_t k = 0; k < node_tags.size(); ++k) {
    index[node_tags[k]] = points.size();
    points.emplace_back(coords[3 * k], coords[3 * k + 1], dim == 2 ? 0.0 : coords[3 * k + 2]);
  }
  auto at = [&](std::size_t tag) {
    const auto it = index.find(tag);
    if (it == index.end()) throw SurfaceMeshError(path + ": an element names a missing node");
    return it->second;
  };
  // Boundary facets: the element faces (edges in 2D) that only one element has.
  std::map<std::vector<std::size_t>, std::vector<std::size_t>> facets;
  const int per = dim == 2 ? 2 : 3;
  const int faces_per_element = dim == 2 ? 3 : 4;
  for (std::size_t e = 0; e < element_tags.size(); ++e) {
    const std::size_t* n = &element_nodes[static_cast<std::size_t>(corners) * e];
    for (int f = 0; f < faces_per_element; ++f) {
      std::vector<std::size_t> v;
      for (int c = 0; c < per; ++c) v.push_back(at(n[(f + c) % corners]));
      std::vector<std::size_t> key = v;
      std::sort(key.begin(), key.end());
      auto [it, fresh] = facets.emplace(key, v);
      if (!fresh) facets.erase(it);
    }
  }
  std::vector<std::array<std::size_t, 3>> faces;
  if (dim == 3) {
    for (const auto& [key, v] : facets) faces.push_back({v[0], v[1], v[2]});
    return solid_from_soup(path, std::move(points), std::move(faces));
  }
  // 2D: the region as a prism about z = 0 (queries lie on z = 0): the triangles at z = -h and
  // z = +h and a wall on every boundary edge.
  const std::size_t n = points.size();
  double h = 0;
  for (const Point& p : points) h = std::max({h, std::abs(p.x()), std::abs(p.y())});
  h = h > 0 ? h : 1.0;
  std::vector<Point> prism;
  for (const Point& p : points) prism.emplace_back(p.x(), p.y(), -h);
  for (const Point& p : points) prism.emplace_back(p.x(), p.y(), h);
  for (std::size_t e = 0; e < element_tags.size(); ++e) {
    const std::size_t a = at(element_nodes[3 * e]), b = at(element_nodes[3 * e + 1]),
                      c = at(element_nodes[3 * e + 2]);
    faces.push_back({a, c, b});
    faces.push_back({n + a, n + b, n + c});
  }
  for (const auto& [key, v] : facets) {
    faces.push_back({v[0], v[1], n + v[1]});
    faces.push_back({v[0], n + v[1], n + v[0]});
  }
  return solid_from_soup(path, std::move(prism), std::move(faces));
}

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
  refuse_self_intersection(path, mesh);
  if (!(std::abs(PMP::volume(mesh)) > 0))
    throw SurfaceMeshError(path + ": the surface encloses no volume");
  return std::make_shared<CgalSolid>(std::move(mesh));
}

}  // namespace periadapt
