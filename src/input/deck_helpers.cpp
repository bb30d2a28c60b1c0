// Helpers shared by the deck's section parsers (input/deck_*.cpp): regions, components, time
// functions, and the folder of the deck being read.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "core/expression.hpp"
#include "input/deck_sections.hpp"
#include "input/yaml_section.hpp"
#include "discretize/surface_mesh.hpp"
#include "input/point_cloud.hpp"

namespace periadapt::deck_sections {


Vec3 to_vec(const std::vector<double>& v) {
  Vec3 p{0, 0, 0};
  for (std::size_t d = 0; d < v.size() && d < 3; ++d) p[d] = v[d];
  return p;
}

// A simple polygon: 3 ... 1000 vertices [x, y] in order, no edge crossing another, area > 0.
std::vector<Vec3> parse_polygon(Section& s) {
  const YAML::Node n = s.raw("polygon");
  if (!n.IsSequence() || n.size() < 3 || n.size() > 1000)
    s.fail("polygon", "expected a list of 3 ... 1000 vertices [x, y], in order around the polygon");
  std::vector<Vec3> v;
  for (const YAML::Node& e : n) {
    if (!e.IsSequence() || e.size() != 2 || !e[0].IsScalar() || !e[1].IsScalar())
      s.fail_at(e, "polygon", "each vertex is [x, y]");
    Vec3 p{0, 0, 0};
    for (int d = 0; d < 2; ++d) {
      try {
        p[d] = e[d].as<double>();
      } catch (const YAML::Exception&) {
        s.fail_at(e, "polygon", "each vertex is [x, y] with numbers, got '" + e[d].Scalar() + "'");
      }
      if (!std::isfinite(p[d])) s.fail_at(e, "polygon", "vertex coordinates must be finite");
    }
    v.push_back(p);
  }
  // Twice the signed area, against the bounding box's (round-off of collinear vertices aside).
  double area2 = 0, lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    area2 += v[j][0] * v[i][1] - v[i][0] * v[j][1];
    for (int d = 0; d < 2; ++d) lo[d] = std::min(lo[d], v[i][d]), hi[d] = std::max(hi[d], v[i][d]);
  }
  if (!(std::abs(area2) > 1e-12 * (hi[0] - lo[0]) * (hi[1] - lo[1])))
    s.fail("polygon", "the polygon has no area");
  const std::size_t m = v.size();
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t k = i + 1; k < m; ++k) {
      if (k == i + 1 || (i == 0 && k == m - 1)) continue;  // neighbours share a vertex
      const Vec3 &a = v[i], &b = v[(i + 1) % m], &c = v[k], &d = v[(k + 1) % m];
      const double o1 = orient2d(a, b, c), o2 = orient2d(a, b, d), o3 = orient2d(c, d, a),
                   o4 = orient2d(c, d, b);
      if (((o1 > 0) != (o2 > 0) || o1 == 0 || o2 == 0) && ((o3 > 0) != (o4 > 0) || o3 == 0 || o4 == 0) &&
          std::max(std::min(a[0], b[0]), std::min(c[0], d[0])) <= std::min(std::max(a[0], b[0]), std::max(c[0], d[0])) &&
          std::max(std::min(a[1], b[1]), std::min(c[1], d[1])) <= std::min(std::max(a[1], b[1]), std::max(c[1], d[1])))
        s.fail("polygon", "edges " + std::to_string(i + 1) + " and " + std::to_string(k + 1) +
                              " cross or touch: the polygon must be simple (list the vertices in "
                              "order around it)");
    }
  return v;
}

// The folder of the deck being read: files a deck names (CAD surfaces, point clouds) are found
// relative to it.
static thread_local std::filesystem::path g_deck_folder;
std::filesystem::path deck_folder() { return g_deck_folder; }
// The grid spacing (node-set regions cover their nodes' cells).
static thread_local double g_grid_spacing = 0;
void set_grid_spacing(double dx) { g_grid_spacing = dx; }

Shape parse_region(Section s, int dim) {
  Shape sh;
  const std::size_t D = static_cast<std::size_t>(dim);
  int kinds = s.has("box") + s.has("disk") + s.has("cylinder") + s.has("sphere") +
              s.has("polygon") + s.has("surface") + s.has("gmsh") + s.has("node_set") + s.has("all");
  if (kinds != 1)
    s.fail("", "a region needs exactly one of: box, disk (2D), polygon (2D), cylinder (3D), "
               "sphere (3D), surface (3D), gmsh, node_set, all");
  if (s.has("node_set")) {
    // The nodes of one block of a point cloud (its optional block column), as their cells.
    Section ns = s.section("node_set");
    std::filesystem::path file = ns.text("points");
    if (file.is_relative()) file = deck_folder() / file;
    const long block = ns.integer("block", std::nullopt, [](long v) {
      return v >= 0 ? std::string() : std::string("a block id is >= 0");
    });
    std::vector<long> blocks;
    std::vector<std::array<double, 4>> pts;
    try {
      pts = read_point_cloud(file.string(), dim, &blocks);
    } catch (const PointCloudError& e) {
      ns.fail("points", e.what());
    }
    if (blocks.empty()) ns.fail("points", file.string() + " has no block column (header ...,volume,block)");
    auto cells = std::make_shared<std::vector<Vec3>>();
    for (std::size_t k = 0; k < pts.size(); ++k)
      if (blocks[k] == block) cells->push_back({pts[k][0], pts[k][1], pts[k][2]});
    if (cells->empty()) ns.fail("block", "no point of " + file.string() + " is in block " + std::to_string(block));
    std::sort(cells->begin(), cells->end());
    ns.finish();
    sh.kind = Shape::Kind::NodeSet;
    sh.cells = std::move(cells);
    sh.half = 0.5 * g_grid_spacing;
  } else if (s.has("gmsh")) {
    if (dim < 2) s.fail("gmsh", "a Gmsh region is for 2D and 3D models");
    std::filesystem::path file = s.text("gmsh");
    if (file.is_relative()) file = deck_folder() / file;
    sh.kind = Shape::Kind::Surface;
    try {
      sh.solid = load_gmsh_solid(file.string(), dim);
    } catch (const SurfaceMeshError& e) {
      s.fail("gmsh", e.what());
    }
  } else if (s.has("surface")) {
    if (dim != 3) s.fail("surface", "a surface region (a closed CAD surface) is for 3D models");
    std::filesystem::path file = s.text("surface");
    if (file.is_relative()) file = deck_folder() / file;
    sh.kind = Shape::Kind::Surface;
    try {
      sh.solid = load_solid_surface(file.string());
    } catch (const SurfaceMeshError& e) {
      s.fail("surface", e.what());
    }
  } else if (s.has("polygon")) {
    if (dim != 2) s.fail("polygon", "a polygon region is for 2D models");
    sh.kind = Shape::Kind::Polygon;
    sh.vertices = parse_polygon(s);
  } else if (s.has("all")) {
    s.boolean("all");
    sh.kind = Shape::Kind::All;
  } else if (s.has("box")) {
    Section b = s.section("box");
    std::vector<double> lo = b.numbers("min", D, D), hi = b.numbers("max", D, D);
    sh.kind = Shape::Kind::Box;
    for (std::size_t d = 0; d < D; ++d) {
      if (!(hi[d] >= lo[d])) b.fail("max", "every max coordinate must be >= the min coordinate");
      sh.box.lo[d] = lo[d];
      sh.box.hi[d] = hi[d];
    }
    b.finish();
  } else {
    const std::string k = s.has("disk") ? "disk" : s.has("cylinder") ? "cylinder" : "sphere";
    if (k == "disk" && dim != 2) s.fail(k, "a disk region is for 2D models; use cylinder or sphere in 3D");
    if (k != "disk" && dim != 3) s.fail(k, "cylinder and sphere regions are for 3D models");
    Section c = s.section(k);
    sh.kind = k == "disk" ? Shape::Kind::Disk : k == "cylinder" ? Shape::Kind::Cylinder
                                                                : Shape::Kind::Sphere;
    sh.center = to_vec(c.numbers("center", D, D));
    sh.radius = c.number("radius", std::nullopt, positive());
    if (k == "cylinder") {
      std::string ax = c.choice("axis", {"x", "y", "z"}, "z");
      sh.axis = ax == "x" ? 0 : ax == "y" ? 1 : 2;
    }
    c.finish();
  }
  sh.outside = s.boolean("outside", false);
  s.finish();
  return sh;
}

std::array<std::optional<std::string>, 3> parse_components(Section& s, const std::string& key,
                                                           int dim, std::array<DeckPlace, 3>* at) {
  std::array<std::optional<std::string>, 3> out;
  YAML::Node n = s.raw(key);
  if (!n.IsSequence() || static_cast<int>(n.size()) != dim)
    s.fail(key, "expected a list of " + std::to_string(dim) +
                    " components (number, expression in x, y, z, t, or null for free)");
  for (int d = 0; d < dim; ++d) {
    const YAML::Node e = n[d];
    if (e.IsNull()) continue;
    if (!e.IsScalar()) s.fail_at(e, key, "each component is a number, an expression or null");
    try {
      Expression test(e.Scalar());
      double v = test(0, 0, 0, 0);
      if (!std::isfinite(v) && test.is_constant()) throw std::invalid_argument("not finite");
    } catch (const std::invalid_argument& ex) {
      s.fail_at(e, key, std::string(ex.what()) +
                            "; allowed: a number or an expression of x, y, z, t (muparser syntax)");
    }
    out[d] = e.Scalar();
    if (at)
      (*at)[d] = {s.key_path(key) + "[" + std::to_string(d) + "]", e.Mark().line + 1,
                  e.Mark().column + 1};
  }
  return out;
}

TimeFunction parse_time(std::optional<Section> s) {
  TimeFunction f;
  if (!s) return f;
  const std::string kind = s->choice("function", {"step", "ramp", "table"}, "step");
  if (kind == "step") {
    f.kind = TimeFunction::Kind::Step;
    f.t0 = s->number("start", 0.0, non_negative());
  } else if (kind == "ramp") {
    f.kind = TimeFunction::Kind::Ramp;
    f.t0 = s->number("start", 0.0, non_negative());
    f.t1 = s->number("end", std::nullopt, positive());
    if (!(f.t1 > f.t0)) s->fail("end", "ramp end must be later than its start");
  } else {
    f.kind = TimeFunction::Kind::Table;
    f.times = s->numbers("times", 2, 100000);
    f.values = s->numbers("values", 2, 100000);
    if (f.times.size() != f.values.size())
      s->fail("values", "needs as many values as times (" + std::to_string(f.times.size()) + ")");
    for (std::size_t k = 1; k < f.times.size(); ++k)
      if (!(f.times[k] > f.times[k - 1])) s->fail("times", "times must increase strictly");
  }
  s->finish();
  return f;
}

bool segment_meets_body(const Box& body, const Vec3& a, const Vec3& b, int dim) {
  for (int k = 0; k <= 200; ++k) {
    Vec3 p = add(a, scale(sub(b, a), k / 200.0));
    Box bb = body;
    for (int d = dim; d < 3; ++d) bb.lo[d] = -INFINITY, bb.hi[d] = INFINITY;
    if (bb.contains(p)) return true;
  }
  return false;
}


void set_deck_folder(const std::filesystem::path& folder) { g_deck_folder = folder; }

double check_bond_based_poisson(Section& s, double nu_bb, const std::string& whose) {
  const double nu = s.number("poisson_ratio");
  if (std::abs(nu - nu_bb) > 1e-3)
    s.fail("poisson_ratio", "the bond-based PMB model fixes Poisson's ratio " + whose + "to " +
                                std::string(nu_bb > 0.3 ? "1/3 (plane stress)"
                                                        : "1/4 (1D, 3D, plane strain)") +
                                "; omit the key or give that value");
  return nu;
}

void parse_fracture_keys(Section& s, std::optional<double>& G0, std::optional<double>& s0) {
  if (s.has("fracture_energy") && s.has("critical_stretch"))
    s.fail("critical_stretch", "give either fracture_energy or critical_stretch, not both");
  if (s.has("fracture_energy")) G0 = s.number("fracture_energy", std::nullopt, positive());
  if (s.has("critical_stretch")) s0 = s.number("critical_stretch", std::nullopt, positive());
}

}  // namespace periadapt::deck_sections
