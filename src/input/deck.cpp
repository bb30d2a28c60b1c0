#include "input/deck.hpp"
#include "input/point_cloud.hpp"
#include "discretize/surface_mesh.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/expression.hpp"
#include "input/yaml_section.hpp"

namespace periadapt {

namespace {

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
static std::filesystem::path deck_folder() { return g_deck_folder; }

Shape parse_region(Section s, int dim) {
  Shape sh;
  const std::size_t D = static_cast<std::size_t>(dim);
  int kinds = s.has("box") + s.has("disk") + s.has("cylinder") + s.has("sphere") +
              s.has("polygon") + s.has("surface") + s.has("gmsh") + s.has("all");
  if (kinds != 1)
    s.fail("", "a region needs exactly one of: box, disk (2D), polygon (2D), cylinder (3D), "
               "sphere (3D), surface (3D), gmsh, all");
  if (s.has("gmsh")) {
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
                                                           int dim) {
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

}  // namespace

namespace {
Deck parse_deck_sections(const std::string& text, const std::string& name,
                         const std::vector<std::string>& overrides);

// A copy without source marks: an error on an overridden key names the key, not a line of the
// deck file (the value came from the command line).
YAML::Node unmarked(const YAML::Node& n) {
  if (n.IsScalar()) return YAML::Node(n.Scalar());
  YAML::Node out;
  if (n.IsSequence())
    for (const YAML::Node& e : n) out.push_back(unmarked(e));
  else if (n.IsMap())
    for (const auto& kv : n) out[unmarked(kv.first)] = unmarked(kv.second);
  return out;
}

// Sets root[a][b]... = value for one "a.b...=value" override.
void apply_override(YAML::Node root, const std::string& name, const std::string& kv) {
  const auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0)
    throw DeckError(name, 0, 0, "", "--set '" + kv + "': expected key.path=value");
  const std::string path = kv.substr(0, eq);
  std::vector<std::string> keys;
  for (std::size_t b = 0;;) {
    const auto dot = path.find('.', b);
    keys.push_back(path.substr(b, dot == std::string::npos ? std::string::npos : dot - b));
    if (keys.back().empty())
      throw DeckError(name, 0, 0, "", "--set '" + kv + "': empty key in the path");
    if (dot == std::string::npos) break;
    b = dot + 1;
  }
  YAML::Node value;
  try {
    value = unmarked(YAML::Load(kv.substr(eq + 1)));
  } catch (const YAML::Exception& e) {
    throw DeckError(name, 0, 0, path, "--set: the value is not YAML: " + e.msg);
  }
  YAML::Node node = root;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::string& key = keys[k];
    const bool last = k + 1 == keys.size();
    if (node.IsSequence()) {
      const bool digits = key.find_first_not_of("0123456789") == std::string::npos;
      const std::size_t at = digits && key.size() < 10 ? std::stoul(key) : node.size();
      if (at >= node.size())
        throw DeckError(name, 0, 0, path,
                        "--set: '" + key + "' is not an index of that list (0 ... " +
                            std::to_string(node.size()) + " - 1)");
      if (last) {
        node[at] = value;
        return;
      }
      node.reset(node[at]);
      continue;
    }
    if (!node.IsMap() && !node.IsNull())
      throw DeckError(name, 0, 0, path, "--set: '" + key + "' is below a single value");
    if (last) {
      node[key] = value;
      return;
    }
    if (!node[key]) node[key] = YAML::Node(YAML::NodeType::Map);
    node.reset(node[key]);
  }
}
}  // namespace

Deck parse_deck(const std::string& text, const std::string& name,
                const std::vector<std::string>& overrides) {
  // Every path out of the loader is a DeckError: a yaml-cpp exception that a section's own
  // checks did not turn into one still names the file and the line.
  try {
    return parse_deck_sections(text, name, overrides);
  } catch (const YAML::Exception& e) {
    throw DeckError(name, e.mark.is_null() ? 0 : e.mark.line + 1,
                    e.mark.is_null() ? 0 : e.mark.column + 1, "",
                    "cannot read this YAML: " + e.msg);
  }
}

namespace {
Deck parse_deck_sections(const std::string& text, const std::string& name,
                         const std::vector<std::string>& overrides) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw DeckError(name, e.mark.line + 1, e.mark.column + 1, "",
                    "malformed YAML: " + e.msg + " (check indentation, colons and brackets)");
  }
  if (root.IsMap())
    for (const std::string& kv : overrides) apply_override(root, name, kv);
  if (!root.IsMap())
    throw DeckError(name, 0, 0, "", "a deck is a YAML mapping with sections model, material, "
                                    "discretization, ... (see docs/deck-reference.md)");
  Deck dk;
  dk.file = name;
  g_deck_folder = std::filesystem::path(name).parent_path();
  {
    // What a checkpoint must agree with: the deck without its output section and run length
    // (a restart may write elsewhere or run longer), comments and layout aside.
    YAML::Node physics = YAML::Clone(root);
    physics.remove("output");
    if (const YAML::Node& cp = physics; cp["solver"] && cp["solver"].IsMap()) {
      physics["solver"].remove("end_time");
      physics["solver"].remove("steps");
    }
    dk.physics_text = YAML::Dump(physics);
  }
  Section top(root, "", name);

  // --- model
  {
    Section m = top.section("model");
    dk.dim = static_cast<int>(m.integer("dimension", std::nullopt, [](long v) {
      return (v >= 1 && v <= 3) ? std::string() : std::string("must be 1, 2 or 3");
    }));
    if (dk.dim == 2) {
      std::string p = m.choice("plane", {"stress", "strain"}, "stress");
      dk.plane = p == "stress" ? PlaneCondition::Stress : PlaneCondition::Strain;
    } else if (m.has("plane")) {
      m.fail("plane", "only 2D models have a plane condition");
    }
    dk.thickness = m.number("thickness", 1.0, positive());
    if (dk.dim == 3 && m.has("thickness")) m.fail("thickness", "3D models have no thickness key");
    dk.formulation = m.choice("formulation", {"pmb", "lps"}, "pmb");
    if (dk.formulation == "lps" && dk.dim == 1)
      m.fail("formulation", "the state-based LPS model is for 2D and 3D; use pmb in 1D");
    m.finish();
  }
  // --- material
  {
    Section s = top.section("material");
    dk.material_name = s.text("name", "material");
    dk.E = s.number("youngs_modulus", std::nullopt, positive());
    dk.rho = s.number("density", std::nullopt, positive());
    const double nu_bb = bond_based_poisson(dk.dim, dk.plane);
    if (dk.formulation == "lps") {
      dk.nu = s.number("poisson_ratio", std::nullopt, [](double v) {
        return (v > -1.0 && v < 0.5) ? std::string()
                                     : std::string("must be in (-1, 0.5) for the LPS model");
      });
    } else if (s.has("poisson_ratio")) {
      dk.nu = s.number("poisson_ratio");
      if (std::abs(*dk.nu - nu_bb) > 1e-3)
        s.fail("poisson_ratio", "the bond-based PMB model fixes Poisson's ratio to " +
                                    std::string(nu_bb > 0.3 ? "1/3 (plane stress)"
                                                            : "1/4 (1D, 3D, plane strain)") +
                                    "; omit the key or give that value");
    }
    if (s.has("fracture_energy") && s.has("critical_stretch"))
      s.fail("critical_stretch", "give either fracture_energy or critical_stretch, not both");
    if (s.has("fracture_energy")) dk.G0 = s.number("fracture_energy", std::nullopt, positive());
    if (s.has("critical_stretch")) dk.s0 = s.number("critical_stretch", std::nullopt, positive());
    dk.thermal_strain = s.number("thermal_strain", 0.0, [](double v) {
      return std::abs(v) < 0.1 ? std::string()
                               : std::string("alpha dT is a small strain: |value| < 0.1");
    });
    std::string sh = s.choice("micromodulus", {"constant", "triangular", "inverted_triangular"},
                              "constant");
    dk.shape = sh == "constant"     ? InfluenceShape::Constant
               : sh == "triangular" ? InfluenceShape::Triangular
                                    : InfluenceShape::InvertedTriangular;
    s.finish();
  }
  // --- discretization
  {
    Section s = top.section("discretization");
    GridSpec& g = dk.grid;
    g.dim = dk.dim;
    g.thickness = dk.thickness;
    g.spacing = s.number("spacing", std::nullopt, positive());
    if (s.has("horizon") && s.has("horizon_factor"))
      s.fail("horizon", "give either horizon or horizon_factor (m), not both");
    if (s.has("horizon")) {
      dk.horizon = s.number("horizon", std::nullopt, positive());
      dk.horizon_factor = dk.horizon / g.spacing;
      if (dk.horizon_factor < 1.0)
        s.fail("horizon", "the horizon must be at least one grid spacing (m = delta/dx >= 1)");
    } else {
      dk.horizon_factor = s.number("horizon_factor", 3.0, [](double v) {
        return v >= 1.0 ? std::string()
                        : std::string("m = delta/dx must be >= 1 (typical 3 to 6)");
      });
      dk.horizon = dk.horizon_factor * g.spacing;
    }
    Section body = s.section("body");
    if (body.has("points")) {
      // A point cloud: the nodes as given, the body their cells' bounding box.
      std::filesystem::path file = body.text("points");
      if (file.is_relative()) file = deck_folder() / file;
      try {
        g.points = read_point_cloud(file.string(), dk.dim);
      } catch (const PointCloudError& e) {
        body.fail("points", e.what());
      }
      body.finish();
      for (int d = 0; d < 3; ++d) {
        g.body.lo[d] = d < dk.dim ? INFINITY : 0.0;
        g.body.hi[d] = d < dk.dim ? -INFINITY : 0.0;
      }
      for (const auto& q : g.points)
        for (int d = 0; d < dk.dim; ++d) {
          g.body.lo[d] = std::min(g.body.lo[d], q[d] - 0.5 * g.spacing);
          g.body.hi[d] = std::max(g.body.hi[d], q[d] + 0.5 * g.spacing);
        }
    }
    Shape b = g.points.empty() ? parse_region(body, dk.dim) : Shape{};
    if (!g.points.empty()) {
      b.kind = Shape::Kind::Box;
      b.box = g.body;
    }
    if (b.outside) s.fail("body", "the body cannot be an outside (complement) region");
    if (b.kind == Shape::Kind::Disk) {
      // A disk body: its bounding box, clipped to the disk.
      g.clip = b;
      for (int d = 0; d < 2; ++d) {
        g.body.lo[d] = b.center[d] - b.radius;
        g.body.hi[d] = b.center[d] + b.radius;
      }
    } else if (b.kind == Shape::Kind::Polygon) {
      // A polygon body: its bounding box, clipped to the polygon.
      g.clip = b;
      for (int d = 0; d < 2; ++d) {
        g.body.lo[d] = INFINITY;
        g.body.hi[d] = -INFINITY;
        for (const Vec3& p : b.vertices) {
          g.body.lo[d] = std::min(g.body.lo[d], p[d]);
          g.body.hi[d] = std::max(g.body.hi[d], p[d]);
        }
      }
    } else if (b.kind == Shape::Kind::Surface) {
      // A CAD solid: its bounding box, clipped to the solid.
      g.clip = b;
      g.body = b.solid->bounds();
    } else if (b.kind != Shape::Kind::Box) {
      s.fail("body", "the body is a box, a disk or polygon in 2D, a closed surface in 3D, or a "
                     "point cloud (use holes to cut it)");
    } else {
      g.body = b.box;
    }
    for (int d = 0; d < dk.dim; ++d)
      if (!(g.body.hi[d] - g.body.lo[d] >= g.spacing))
        s.fail("body", "the body must be at least one grid spacing wide in every direction");
    g.rotation_deg = s.number("rotation_deg", 0.0, in_range(-360, 360));
    if (g.rotation_deg != 0.0 && dk.dim != 2)
      s.fail("rotation_deg", "grid rotation is available for 2D models only");
    if (g.rotation_deg != 0.0 && !g.points.empty())
      s.fail("rotation_deg", "a point-cloud body keeps its nodes as given; rotate the points instead");
    Vec3 centre{0, 0, 0};
    for (int d = 0; d < 3; ++d)
      centre[d] = d < dk.dim ? 0.5 * (g.body.lo[d] + g.body.hi[d]) : 0.0;
    g.pivot = s.has("rotation_pivot") ? to_vec(s.numbers("rotation_pivot", 2, 2)) : centre;
    std::string reg = s.choice("registration", {"cell_centered", "node_on_edge"}, "cell_centered");
    g.registration = reg == "cell_centered" ? Registration::CellCentered : Registration::NodeOnEdge;
    for (Section h : s.list("holes")) g.holes.push_back(parse_region(h, dk.dim));
    std::string q =
        s.choice("quadrature", {"pa_pdlammps", "ipa_hybrid", "subcell", "full"}, "pa_pdlammps");
    if (q == "ipa_hybrid" && dk.dim != 2)
      s.fail("quadrature", "ipa_hybrid is a 2D rule; use subcell (accurate covered volumes) in " +
                               std::to_string(dk.dim) + "D");
    // true keeps its old meaning (the energy method); moments also fixes the axis coupling.
    const std::string sc =
        s.choice("surface_correction", {"false", "true", "energy", "moments"}, "false");
    dk.surface_correction = sc == "moments"                   ? SurfaceCorrection::Moments
                            : sc == "true" || sc == "energy" ? SurfaceCorrection::Energy
                                                              : SurfaceCorrection::None;
    dk.quadrature = q == "full"         ? Quadrature::Full
                    : q == "subcell"    ? Quadrature::Subcell
                    : q == "ipa_hybrid" ? Quadrature::IpaHybrid
                                        : Quadrature::PaPdlammps;
    s.finish();
  }
  // --- cracks
  for (Section c : top.list("cracks")) {
    PreCrack pc;
    if (dk.dim == 1) c.fail("", "pre-cracks are for 2D (segment) and 3D (quad) models");
    if (dk.dim == 2) {
      auto pts = c.points("segment", 2, 2);
      pc.points[0] = to_vec(pts[0]);
      pc.points[1] = to_vec(pts[1]);
      if (norm(sub(pc.points[1], pc.points[0])) <= 0)
        c.fail("segment", "the two crack ends must differ");
      if (!segment_meets_body(dk.grid.body, pc.points[0], pc.points[1], 2))
        c.fail("segment", "the crack lies outside the body; it must cross or touch the body box");
    } else {
      auto pts = c.points("quad", 4, 3);
      pc.planar3d = true;
      for (int k = 0; k < 4; ++k) pc.points[k] = to_vec(pts[static_cast<std::size_t>(k)]);
      bool meets = false;
      for (int k = 0; k < 4 && !meets; ++k)
        meets = segment_meets_body(dk.grid.body, pc.points[k], pc.points[(k + 2) % 4], 3) ||
                segment_meets_body(dk.grid.body, pc.points[k], pc.points[(k + 1) % 4], 3);
      if (!meets) c.fail("quad", "the crack lies outside the body; it must cross the body box");
      Vec3 nrm = cross(sub(pc.points[1], pc.points[0]), sub(pc.points[3], pc.points[0]));
      if (norm(nrm) <= 0) c.fail("quad", "the quadrilateral is degenerate");
      const double off = std::abs(dot(nrm, sub(pc.points[2], pc.points[0]))) / norm(nrm);
      if (off > 1e-9 * norm(sub(pc.points[2], pc.points[0])) + 1e-12)
        c.fail("quad", "the four corners must lie in one plane");
    }
    c.finish();
    dk.cracks.push_back(pc);
  }
  // --- loads
  for (Section l : top.list("loads")) {
    LoadSpec ls;
    std::string t = l.choice("type", {"traction", "body_force"});
    ls.kind = t == "traction" ? LoadSpec::Kind::Traction : LoadSpec::Kind::BodyForce;
    ls.name = l.text("name", l.path());
    ls.region = parse_region(l.section("region"), dk.dim);
    ls.value = to_vec(l.numbers("value", static_cast<std::size_t>(dk.dim),
                                static_cast<std::size_t>(dk.dim)));
    if (ls.kind == LoadSpec::Kind::Traction) ls.layer = l.number("layer", 0.0, non_negative());
    ls.time = parse_time(l.optional_section("time"));
    l.finish();
    dk.loads.push_back(ls);
  }
  // --- boundary conditions
  for (Section b : top.list("boundary_conditions")) {
    MotionSpec ms;
    ms.name = b.text("name", b.path());
    ms.region = parse_region(b.section("region"), dk.dim);
    if (b.has("velocity") == b.has("displacement"))
      b.fail("", "a boundary condition needs exactly one of: velocity, displacement");
    const bool vel = b.has("velocity");
    ms.kind = vel ? MotionSpec::Kind::Velocity : MotionSpec::Kind::Displacement;
    ms.component = parse_components(b, vel ? "velocity" : "displacement", dk.dim);
    b.finish();
    dk.motions.push_back(ms);
  }
  // --- initial conditions
  if (auto ic = top.optional_section("initial_conditions")) {
    if (ic->has("displacement")) dk.initial_displacement = parse_components(*ic, "displacement", dk.dim);
    if (ic->has("velocity")) dk.initial_velocity = parse_components(*ic, "velocity", dk.dim);
    ic->finish();
  }
  // --- damage
  if (auto dmg = top.optional_section("damage")) {
    dk.damage = dmg->boolean("enabled", true);
    for (Section r : dmg->list("no_fail")) dk.no_fail.push_back(parse_region(r, dk.dim));
    if (auto pd = dmg->optional_section("overlay")) {
      // Stewart & Jeon 2019 refinement overlay: bonds re-checked on a virtual sub-grid dx / n.
      dk.pdro.enabled = true;
      dk.pdro.n = pd->number("n", std::nullopt, [](double v) {
        return (v > 1.0 && v <= 20.0) ? std::string()
                                      : std::string("the sub-grid ratio dx/dx' must be in (1, 20]");
      });
      if (pd->has("region")) dk.pdro.region = parse_region(pd->section("region"), dk.dim);
      dk.pdro.interpolation = pd->choice("interpolation", {"pddo", "pim"}, "pddo") == "pim"
                                  ? PdroInterpolation::Pim
                                  : PdroInterpolation::Pddo;
      dk.pdro.weight = pd->choice("weight", {"uniform", "gaussian"}, "uniform") == "gaussian"
                           ? PddoWeight::Gaussian
                           : PddoWeight::Uniform;
      dk.pdro.sampling = pd->choice("sampling", {"three_pairs", "whole_bond"}, "three_pairs") == "whole_bond"
                             ? PdroSampling::WholeBond
                             : PdroSampling::ThreePairs;
      pd->finish();
      // (bond_pairing is read later: checked below with the solver section)
    }
    dmg->finish();
  }
  // --- solver
  {
    Section s = top.section("solver");
    const std::string type = s.choice("type", {"explicit", "static", "relaxation"}, "explicit");
    if (s.has("memory_limit_gb"))
      dk.memory_limit_gb = s.number("memory_limit_gb", std::nullopt, [](double v) {
        return (v > 0 && v <= 1e6) ? std::string() : std::string("must be in (0, 1e6] GB");
      });
    dk.solver = type == "static"       ? Deck::SolverType::Static
                : type == "relaxation" ? Deck::SolverType::Relaxation
                                       : Deck::SolverType::Explicit;
    if (dk.solver == Deck::SolverType::Relaxation) {
      for (const char* k : {"time_step", "end_time", "steps", "safety_factor", "multirate",
                            "multirate_ratio", "allow_unstable_time_step"})
        if (s.has(k))
          s.fail(k, "dynamic relaxation has no physical time step; use load_steps, tolerance "
                    "and max_iterations");
      dk.load_steps = static_cast<int>(s.integer("load_steps", 1, [](long v) {
        return (v >= 1 && v <= 1000000) ? std::string() : std::string("must be in 1 ... 1e6");
      }));
      dk.relax_tolerance = s.number("tolerance", 1e-6, [](double v) {
        return (v > 0 && v < 1) ? std::string() : std::string("a relative residual in (0, 1)");
      });
      dk.relax_max_iterations = s.integer("max_iterations", 200000, [](long v) {
        return v >= 1 ? std::string() : std::string("must be >= 1");
      });
    } else if (dk.solver == Deck::SolverType::Static) {
      if (dk.formulation == "lps")
        s.fail("type", "the linear static solve assembles the bond-based stiffness; for the LPS "
                       "model use type: relaxation");
      // Linearized equilibrium: no time stepping keys, no bond breaking.
      for (const char* k : {"time_step", "end_time", "steps", "safety_factor", "multirate",
                            "multirate_ratio", "allow_unstable_time_step"})
        if (s.has(k))
          s.fail(k, "a static solve has no time stepping; remove this key or use type: explicit");
      dk.damage = false;
    } else {
      if (s.has("time_step")) dk.time_step = s.number("time_step", std::nullopt, positive());
      dk.safety = s.number("safety_factor", 0.8, [](double v) {
        return (v > 0 && v <= 1) ? std::string() : std::string("must be in (0, 1]");
      });
      dk.allow_unstable_time_step = s.boolean("allow_unstable_time_step", false);
      dk.multirate = s.boolean("multirate", false);
      if (s.has("multirate_ratio") && !dk.multirate)
        s.fail("multirate_ratio", "the largest step ratio of multi-rate stepping needs "
                                  "multirate: true");
      dk.multirate_ratio = static_cast<int>(s.integer("multirate_ratio", 2, [](long v) {
        return (v >= 2 && v <= 4) ? std::string() : std::string("an integer 2, 3 or 4");
      }));
      if (dk.multirate && dk.formulation == "lps")
        s.fail("multirate", "multi-rate stepping needs row-local forces: formulation: pmb (the LPS "
                            "dilatation couples every node to its neighbours' rows)");
      if (s.has("end_time") == s.has("steps"))
        s.fail("", "give exactly one of end_time (s) or steps");
      if (s.has("end_time")) dk.end_time = s.number("end_time", std::nullopt, positive());
      if (s.has("steps"))
        dk.steps = s.integer("steps", std::nullopt, [](long v) {
          return v >= 1 ? std::string() : std::string("must be >= 1");
        });
    }
    dk.dual_horizon =
        s.choice("bond_pairing", {"source_horizon", "dual_horizon"}, "source_horizon") ==
        "dual_horizon";
    if (dk.multirate && dk.dual_horizon)
      s.fail("multirate", "multi-rate stepping needs bond_pairing: source_horizon (dual-horizon "
                          "forces act on both ends of a bond)");
    s.finish();
  }
  if (dk.pdro.enabled && dk.dual_horizon)
    top.fail("damage", "the refinement overlay works with bond_pairing: source_horizon (pmb or "
                       "lps); the dual-horizon kernels do not re-check bonds");
  if (dk.thermal_strain != 0.0 &&
      (dk.solver != Deck::SolverType::Explicit || dk.formulation != "pmb" || dk.dual_horizon))
    top.fail("material", "thermal_strain is supported by the explicit pmb solver with "
                         "bond_pairing: source_horizon only");
  if (dk.damage && !dk.G0 && !dk.s0)
    top.fail("material", "damage is enabled: give material.fracture_energy (G0) or "
                         "material.critical_stretch, or set damage.enabled: false");
  // --- adaptive grid refinement and scaling
  if (auto a = top.optional_section("adapt")) {
    AdaptSpec& ad = dk.adapt;
    int initial_top = 0;
    for (Section z : a->list("initial_refinement")) {
      InitialRefinement ir;
      ir.region = parse_region(z.section("region"), dk.dim);
      ir.level = static_cast<int>(z.integer("level", std::nullopt, [](long v) {
        return (v >= 1 && v <= 6) ? std::string() : std::string("must be in 1 ... 6");
      }));
      initial_top = std::max(initial_top, ir.level);
      z.finish();
      ad.initial.push_back(ir);
    }
    ad.visibility = a->boolean("visibility", true);
    ad.max_level = static_cast<int>(a->integer("max_level", std::max(1, initial_top), [](long v) {
      return (v >= 1 && v <= 6) ? std::string() : std::string("must be in 1 ... 6");
    }));
    if (initial_top > ad.max_level)
      a->fail("max_level", "is below the level of an initial_refinement zone (" +
                               std::to_string(initial_top) + ")");
    ad.method = a->choice("method", {"B", "A"}, "B") == "A" ? NodeGeneration::A : NodeGeneration::B;
    const std::string sc = a->choice("scaling", {"delta", "m", "delta_m"}, "delta");
    ad.scaling = sc == "delta" ? HorizonScaling::Delta
                 : sc == "m"   ? HorizonScaling::M
                               : HorizonScaling::DeltaM;
    if (ad.scaling == HorizonScaling::DeltaM) {
      ad.m_per_level = a->numbers("m_per_level", static_cast<std::size_t>(ad.max_level + 1), 64);
      for (double v : ad.m_per_level)
        if (!(v >= 1.0)) a->fail("m_per_level", "every m must be >= 1");
      if (std::abs(ad.m_per_level[0] - dk.horizon_factor) > 1e-9 * dk.horizon_factor)
        a->fail("m_per_level", "the first entry is level 0 and must equal the grid's m = " +
                                   std::to_string(dk.horizon_factor));
    } else if (a->has("m_per_level")) {
      a->fail("m_per_level", "only used with scaling: delta_m");
    }
    ad.start_time = a->number("start_time", 0.0, non_negative());
    ad.check_every = static_cast<int>(a->integer("check_every", 1, [](long v) {
      return v >= 1 ? std::string() : std::string("must be >= 1");
    }));
    if (a->has("energy_trigger"))
      ad.energy_fraction = a->number("energy_trigger", std::nullopt, [](double v) {
        return (v > 0 && v <= 1) ? std::string()
                                 : std::string("a fraction of the maximum energy density in (0, 1]");
      });
    if (a->has("stretch_trigger"))
      ad.stretch_fraction = a->number("stretch_trigger", std::nullopt, [](double v) {
        return (v > 0 && v <= 1) ? std::string()
                                 : std::string("a fraction of the finest level's critical stretch "
                                               "in (0, 1]");
      });
    // A deck that names no trigger and no initial zone gets the triggers that need no tuning:
    // bonds at half the finest level's critical stretch, and damage growth on a coarse node.
    const bool defaults = !ad.energy_fraction && !ad.stretch_fraction &&
                          !a->has("damage_trigger") && ad.initial.empty() &&
                          dk.solver == Deck::SolverType::Explicit;
    if (defaults) ad.stretch_fraction = kDefaultStretchTrigger;
    ad.damage_trigger = a->boolean("damage_trigger", defaults);
    // With the automatic triggers the zone follows the stretch field closely, and its interfaces
    // come near stressed free surfaces: without the correction a crack starts where an interface
    // meets a hole instead of at the hole's stress peak.
    ad.interface_horizon = a->boolean("interface_horizon", defaults);
    ad.refine_loads = a->boolean("refine_loads", defaults && ad.method == NodeGeneration::B);
    if (ad.refine_loads && ad.method == NodeGeneration::A)
      a->fail("refine_loads", "method a shrinks the loaded parents' cells without handing the "
                              "lost load to the new nodes; use method b");
    ad.total_energy = a->choice("energy", {"strain", "total"}, "strain") == "total";
    ad.coarsen = a->boolean("coarsen", false);
    ad.conserve_energy = a->boolean("conserve_energy", false);
    if (ad.coarsen && ad.method == NodeGeneration::A)
      a->fail("coarsen", "coarsening restores parents from their children (method b); method a "
                         "keeps the parents and is not coarsened");
    if (ad.coarsen && !ad.energy_fraction)
      a->fail("coarsen", "coarsening needs the energy trigger (it coarsens where the energy "
                         "is below the trigger level)");
    ad.visibility_factor = a->number("visibility_factor", 1.0, [](double v) {
      return (v >= 1.0 && v <= 20.0) ? std::string() : std::string("must be in [1, 20] horizons");
    });
    ad.enabled = ad.energy_fraction || ad.stretch_fraction || ad.damage_trigger;
    if (!ad.enabled && ad.initial.empty())
      a->fail("", "give at least one trigger (stretch_trigger: fraction of the critical stretch, "
                  "energy_trigger: fraction of W_max, damage_trigger: true) or an "
                  "initial_refinement zone");
    if (ad.enabled && dk.solver != Deck::SolverType::Explicit)
      a->fail("", "refinement triggers work with the explicit solver only; static and relaxation "
                  "runs take initial_refinement zones");
    if (a->has("region")) ad.region = parse_region(a->section("region"), dk.dim);
    a->finish();
  }
  // --- output
  if (auto o = top.optional_section("output")) {
    OutputSpec& out = dk.output;
    out.directory = o->text("directory", out.directory);
    out.vtu = o->boolean("vtu", true);
    out.stress = o->boolean("stress", false);
    out.vtu_zlib = o->choice("vtu_compression", {"none", "zlib"}, "none") == "zlib";
    for (Section r : o->list("regions")) {
      NamedRegion nr;
      nr.name = r.text("name");
      if (nr.name.empty()) r.fail("name", "must not be empty");
      for (const NamedRegion& other : out.regions)
        if (other.name == nr.name) r.fail("name", "'" + nr.name + "' names two output regions");
      nr.region = parse_region(r.section("region"), dk.dim);
      r.finish();
      out.regions.push_back(std::move(nr));
    }
    out.vtu_count = static_cast<int>(o->integer("vtu_snapshots", 10, [](long v) {
      return (v >= 0 && v <= 100000) ? std::string() : std::string("must be in 0 ... 100000");
    }));
    out.history_every = o->integer("history_every", 10, [](long v) {
      return v >= 1 ? std::string() : std::string("must be >= 1");
    });
    out.checkpoint_every = o->integer("checkpoint_every", 0, [](long v) {
      return v >= 0 ? std::string() : std::string("must be >= 0 (0: no periodic checkpoints)");
    });
    if (o->has("png_times")) out.png_times = o->numbers("png_times", 1, 1000);
    out.png_width = static_cast<int>(o->integer("png_width", 1200, [](long v) {
      return (v >= 100 && v <= 8000) ? std::string() : std::string("must be in [100, 8000]");
    }));
    if (auto ld = o->optional_section("load_displacement")) {
      LoadDisplacementPlot p;
      p.name = ld->text("name");
      bool known = false;
      std::string names;
      for (const LoadSpec& l : dk.loads) known = known || l.name == p.name, names += " " + l.name;
      for (const MotionSpec& mo : dk.motions)
        known = known || mo.name == p.name, names += " " + mo.name;
      if (!known)
        ld->fail("name", "'" + p.name + "' names no load or boundary condition; the names are:" +
                             (names.empty() ? std::string(" (none)") : names));
      const std::string c = ld->choice("component", dk.dim == 1   ? std::vector<std::string>{"x"}
                                                    : dk.dim == 2 ? std::vector<std::string>{"x", "y"}
                                                                  : std::vector<std::string>{"x", "y", "z"},
                                       "x");
      p.component = c[0] - 'x';
      ld->finish();
      out.load_displacement = p;
    }
    if (auto ct = o->optional_section("crack_tip")) {
      out.track_tip = true;
      out.tip_threshold = ct->number("threshold", 0.35, in_range(0, 1));
      if (ct->has("origin"))
        out.tip_origin = to_vec(ct->numbers("origin", static_cast<std::size_t>(dk.dim),
                                            static_cast<std::size_t>(dk.dim)));
      if (ct->has("direction")) {
        Vec3 d = to_vec(ct->numbers("direction", static_cast<std::size_t>(dk.dim),
                                    static_cast<std::size_t>(dk.dim)));
        if (norm(d) <= 0) ct->fail("direction", "must be a non-zero vector");
        out.tip_direction = scale(d, 1.0 / norm(d));
      }
      out.tip_side = ct->choice("side", {"both", "upper", "lower"}, "both");
      out.tip_window = ct->number("speed_window", 2e-6, positive());
      if (ct->has("advance")) out.tip_advance = ct->number("advance", std::nullopt, positive());
      if (ct->has("branch_gap")) out.branch_gap = ct->number("branch_gap", std::nullopt, positive());
      ct->finish();
    }
    o->finish();
  }
  if (!dk.output.track_tip && !dk.cracks.empty() && dk.dim == 2) dk.output.track_tip = true;
  top.finish();
  return dk;
}
}  // namespace

Deck load_deck(const std::string& path, const std::vector<std::string>& overrides) {
  // A deck is a small text file: a device, a pipe or a folder would be read without bound.
  constexpr std::uintmax_t kMaxDeckBytes = 16u << 20;
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw DeckError(path, 0, 0, "", "cannot open the deck file");
  if (!std::filesystem::is_regular_file(status))
    throw DeckError(path, 0, 0, "", "is not a regular file; a deck is a YAML text file");
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec || bytes > kMaxDeckBytes)
    throw DeckError(path, 0, 0, "",
                    "the file has " + std::to_string(bytes) + " bytes; a deck has at most " +
                        std::to_string(kMaxDeckBytes) + " (16 MiB)");
  std::ifstream in(path);
  if (!in) throw DeckError(path, 0, 0, "", "cannot open the deck file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_deck(ss.str(), path, overrides);
}

}  // namespace periadapt
