// Deck sections discretization (the body, its lattice and quadrature) and cracks.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/expression.hpp"
#include "input/deck_sections.hpp"
#include "input/yaml_section.hpp"
#include "discretize/surface_mesh.hpp"
#include "input/point_cloud.hpp"

namespace periadapt::deck_sections {

void parse_discretization_and_cracks(Section& top, Deck& dk) {
  // --- discretization
  {
    Section s = top.section("discretization");
    GridSpec& g = dk.grid;
    g.dim = dk.dim;
    g.thickness = dk.thickness;
    g.spacing = s.number("spacing", std::nullopt, positive());
    set_grid_spacing(g.spacing);
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
    dk.body_at = body.place();
    if (body.has("points")) {
      // A point cloud: the nodes as given, the body their cells' bounding box.
      std::filesystem::path file = body.text("points");
      if (file.is_relative()) file = deck_folder() / file;
      try {
        std::vector<long> lines;
        g.points = read_point_cloud(file.string(), dk.dim, nullptr, &lines);
        check_point_cloud_body(file.string(), g.points, lines, dk.dim, g.spacing,
                               cell_volume(dk.dim, g.spacing, g.thickness));
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
    for (Section h : s.list("holes")) {
      dk.holes_at.push_back(h.place());
      g.holes.push_back(parse_region(h, dk.dim));
    }
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
    dk.lattice_calibration =
        s.choice("micromodulus_calibration", {"analytic", "lattice"}, "analytic") == "lattice";
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
    dk.crack_at.push_back(c.place());
  }
}

}  // namespace periadapt::deck_sections
