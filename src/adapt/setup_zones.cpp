#include "adapt/setup_zones.hpp"

#include <algorithm>
#include <cmath>

#include "core/cell_grid.hpp"

namespace periadapt {

namespace {

Vec3 along(const Vec3& p, const Vec3& dir, double s) {
  return {p[0] + s * dir[0], p[1] + s * dir[1], p[2] + s * dir[2]};
}

Vec3 unit(const Vec3& v) {
  const double n = std::sqrt(dot(v, v));
  return n > 0 ? Vec3{v[0] / n, v[1] / n, v[2] / n} : Vec3{0, 0, 0};
}

}  // namespace

std::vector<InitialRefinement> crack_tip_zones(const Model& m, int level) {
  const NodeSet& ns = m.nodes;
  std::vector<InitialRefinement> zones;
  if (m.cracks.empty() || ns.size() == 0) return zones;
  double h = 0, delta = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.flags[i] & kActive) h = std::max(h, ns.spacing[i]), delta = std::max(delta, ns.horizon[i]);
  CellGrid grid(ns.dim, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()}, ns.size(), h);
  auto body_at = [&](const Vec3& p) {
    bool found = false;
    // 0.9 h: above the farthest an interior point lies from its nearest node (sqrt(3)/2 h), below
    // the spacing at which a surface node can sit from a probe beyond the surface.
    grid.for_each_within(p, 0.9 * h, [&](std::uint32_t j, double) {
      found = found || (ns.flags[j] & kActive);
    });
    return found;
  };
  // A front point is kept where the body goes on beyond it along `out` (the crack's own plane,
  // pointing away from the crack).
  auto add = [&](const Vec3& p, const Vec3& out) {
    if (!body_at(along(p, out, h))) return;
    InitialRefinement z;
    z.level = level;
    z.region.kind = ns.dim == 3 ? Shape::Kind::Sphere : Shape::Kind::Disk;
    z.region.center = p;
    z.region.radius = delta;
    // The ball is the front point's visibility ball already: every coarse node that sees the
    // point is in it. Widened once more it doubled the zone (the 3D inclined plate: 22% of the
    // body before the first step).
    z.widen = false;
    zones.push_back(std::move(z));
  };
  for (const PreCrack& c : m.cracks) {
    if (!c.planar3d) {
      const Vec3 d = unit(sub(c.points[1], c.points[0]));
      add(c.points[1], d);
      add(c.points[0], Vec3{-d[0], -d[1], -d[2]});
      continue;
    }
    // Outward in the quad's plane: edge direction x normal, the normal taken from the diagonals so
    // that it follows the vertices' winding (a dart-shaped quad included).
    const Vec3 d1 = sub(c.points[2], c.points[0]), d2 = sub(c.points[3], c.points[1]);
    const Vec3 normal{d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2],
                      d1[0] * d2[1] - d1[1] * d2[0]};
    for (int e = 0; e < 4; ++e) {
      const Vec3 a = c.points[e], b = c.points[(e + 1) % 4];
      const Vec3 t = sub(b, a);
      const double len = std::sqrt(dot(t, t));
      if (!(len > 0)) continue;
      const Vec3 tu = unit(t);
      const Vec3 out = unit(Vec3{tu[1] * normal[2] - tu[2] * normal[1],
                                 tu[2] * normal[0] - tu[0] * normal[2],
                                 tu[0] * normal[1] - tu[1] * normal[0]});
      if (dot(out, out) == 0) continue;
      // Each corner once: an edge's points from its start up to, not including, its end.
      const int n = std::max(1, static_cast<int>(std::ceil(len / h)));
      for (int k = 0; k < n; ++k) add(along(a, tu, len * k / n), out);
    }
  }
  return zones;
}

bool component_moves(bool velocity, const Expression& c) {
  return velocity ? !(c.is_constant() && c(0, 0, 0, 0) == 0.0) : c.depends_on_time();
}

namespace {

// Whether some node of `nodes` has every bond of its family ending in `nodes`.
bool holds_a_whole_family(const Model& m, const std::vector<std::uint32_t>& nodes) {
  const BondFamilies& bf = m.bonds;
  std::vector<char> in(m.nodes.size(), 0);
  for (std::uint32_t i : nodes) in[i] = 1;
  for (std::uint32_t i : nodes) {
    if (i >= bf.num_nodes() || bf.end(i) == bf.begin(i)) continue;
    bool whole = true;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i) && whole; ++k) whole = in[bf.neighbor[k]];
    if (whole) return true;
  }
  return false;
}

}  // namespace

std::vector<InitialRefinement> driven_patch_zones(const Model& m, int level) {
  std::vector<InitialRefinement> zones;
  for (const PrescribedMotion& pm : m.motions) {
    bool moves = false;
    for (const auto& c : pm.component)
      moves = moves || (c && component_moves(pm.kind == PrescribedMotion::Kind::Velocity, *c));
    if (!moves || pm.nodes.empty() || holds_a_whole_family(m, pm.nodes)) continue;
    InitialRefinement z;
    z.level = level;
    z.region = pm.region;
    zones.push_back(std::move(z));
  }
  return zones;
}

std::vector<InitialRefinement> setup_zones(const Model& m, const AdaptSpec& spec) {
  std::vector<InitialRefinement> zones = spec.initial;
  // Nothing is refined before start_time, nor outside the deck's adapt.region.
  if (!spec.enabled || spec.start_time > 0) return zones;
  const std::size_t own = zones.size();
  if (spec.refine_crack_tips)
    for (InitialRefinement& z : crack_tip_zones(m, spec.max_level)) zones.push_back(std::move(z));
  if (spec.refine_motions)
    for (InitialRefinement& z : driven_patch_zones(m, spec.max_level)) zones.push_back(std::move(z));
  for (std::size_t k = own; k < zones.size(); ++k) zones[k].within = spec.region;
  return zones;
}

}  // namespace periadapt
