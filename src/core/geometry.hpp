#pragma once
// Geometry primitives used to describe bodies, holes, regions and pre-cracks.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

namespace periadapt {

using Vec3 = std::array<double, 3>;

inline Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 scale(const Vec3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

// Axis-aligned box; unused dimensions span (-inf, inf) so the same test works in 1D/2D/3D.
struct Box {
  Vec3 lo{-INFINITY, -INFINITY, -INFINITY};
  Vec3 hi{INFINITY, INFINITY, INFINITY};
  bool contains(const Vec3& p, double tol = 0.0) const {
    for (int d = 0; d < 3; ++d)
      if (p[d] < lo[d] - tol || p[d] > hi[d] + tol) return false;
    return true;
  }
};

// Distance from p to the segment a-b in the xy-plane.
inline double distance_to_segment_2d(const Vec3& p, const Vec3& a, const Vec3& b) {
  const double ex = b[0] - a[0], ey = b[1] - a[1];
  const double len2 = ex * ex + ey * ey;
  double t = len2 > 0 ? ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p[0] - (a[0] + t * ex), p[1] - (a[1] + t * ey));
}

// Even-odd rule: inside a simple polygon (vertices in order, either orientation) of the xy-plane.
inline bool polygon_contains(const std::vector<Vec3>& v, const Vec3& p) {
  bool in = false;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++)
    if ((v[i][1] > p[1]) != (v[j][1] > p[1]) &&
        p[0] < (v[j][0] - v[i][0]) * (p[1] - v[i][1]) / (v[j][1] - v[i][1]) + v[i][0])
      in = !in;
  return in;
}

inline double polygon_boundary_distance(const std::vector<Vec3>& v, const Vec3& p) {
  double d = INFINITY;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++)
    d = std::min(d, distance_to_segment_2d(p, v[j], v[i]));
  return d;
}

// A closed triangulated surface read from a CAD file (discretize/surface_mesh.hpp): its solid's
// inside test and the distance to its surface. Thread-safe const queries.
struct SolidSurface {
  virtual ~SolidSurface() = default;
  virtual bool inside(const Vec3& p) const = 0;  // points on the surface count as inside
  virtual double distance(const Vec3& p) const = 0;
  virtual Box bounds() const = 0;
  virtual double volume() const = 0;
};

// A region of space: box, disk (2D), cylinder along an axis (3D), sphere, polygon (2D) or the
// solid of a closed surface (3D).
struct Shape {
  enum class Kind { Box, Disk, Cylinder, Sphere, Polygon, Surface, NodeSet, All } kind = Kind::All;
  Box box;
  Vec3 center{0, 0, 0};
  double radius = 0;
  int axis = 2;  // cylinder axis (0,1,2)
  std::vector<Vec3> vertices;  // polygon (2D), in order
  std::shared_ptr<const SolidSurface> solid;  // Surface
  // NodeSet: the cells (half-width `half`) of a point cloud's nodes of one block, sorted by x.
  // A set of cells rather than of points, so that children of its nodes belong to it.
  std::shared_ptr<const std::vector<Vec3>> cells;
  double half = 0;
  bool outside = false;  // the complement: everything not in the shape (e.g. a clamped rim)
  bool contains(const Vec3& p, double tol = 0.0) const {
    return outside ? !contains_shape(p, -tol) : contains_shape(p, tol);
  }
  bool contains_shape(const Vec3& p, double tol) const {
    switch (kind) {
      case Kind::All: return true;
      case Kind::Box: return box.contains(p, tol);
      case Kind::Disk: {
        double dx = p[0] - center[0], dy = p[1] - center[1];
        return dx * dx + dy * dy <= (radius + tol) * (radius + tol);
      }
      case Kind::Cylinder: {
        double r2 = 0;
        for (int d = 0; d < 3; ++d)
          if (d != axis) r2 += (p[d] - center[d]) * (p[d] - center[d]);
        return r2 <= (radius + tol) * (radius + tol);
      }
      case Kind::Sphere: {
        Vec3 q = sub(p, center);
        return dot(q, q) <= (radius + tol) * (radius + tol);
      }
      case Kind::Polygon: {
        // tol > 0 widens the polygon by tol (points on its edges count), tol < 0 narrows it.
        const bool in = polygon_contains(vertices, p);
        if (tol == 0.0) return in;
        const double d = polygon_boundary_distance(vertices, p);
        return tol > 0 ? (in || d <= tol) : (in && d > -tol);
      }
      case Kind::Surface: {
        const bool in = solid->inside(p);
        if (tol == 0.0) return in;
        const double d = solid->distance(p);
        return tol > 0 ? (in || d <= tol) : (in && d > -tol);
      }
      case Kind::NodeSet: {
        const double r = half + tol;
        auto it = std::lower_bound(cells->begin(), cells->end(), p[0] - r,
                                   [](const Vec3& q, double x) { return q[0] < x; });
        for (; it != cells->end() && (*it)[0] <= p[0] + r; ++it)
          if (std::abs((*it)[1] - p[1]) <= r && std::abs((*it)[2] - p[2]) <= r) return true;
        return false;
      }
    }
    return false;
  }
  // Distance from p to the shape itself (0 inside; the complement flag is ignored): how close a
  // crack tip came to a hole.
  double distance_to_shape(const Vec3& p) const {
    switch (kind) {
      case Kind::All: return 0.0;
      case Kind::Box: {
        double r2 = 0;
        for (int d = 0; d < 3; ++d) {
          const double e = std::max({box.lo[d] - p[d], 0.0, p[d] - box.hi[d]});
          r2 += e * e;
        }
        return std::sqrt(r2);
      }
      case Kind::Disk: return std::max(0.0, std::hypot(p[0] - center[0], p[1] - center[1]) - radius);
      case Kind::Cylinder: {
        double r2 = 0;
        for (int d = 0; d < 3; ++d)
          if (d != axis) r2 += (p[d] - center[d]) * (p[d] - center[d]);
        return std::max(0.0, std::sqrt(r2) - radius);
      }
      case Kind::Sphere: {
        const Vec3 q = sub(p, center);
        return std::max(0.0, std::sqrt(dot(q, q)) - radius);
      }
      case Kind::Polygon:
        return polygon_contains(vertices, p) ? 0.0 : polygon_boundary_distance(vertices, p);
      case Kind::Surface: return solid->inside(p) ? 0.0 : solid->distance(p);
      case Kind::NodeSet: {
        double best = INFINITY;
        for (const Vec3& q : *cells) {
          double r2 = 0;
          for (int d = 0; d < 3; ++d) {
            const double e = std::max(std::abs(p[d] - q[d]) - half, 0.0);
            r2 += e * e;
          }
          best = std::min(best, r2);
        }
        return std::sqrt(best);
      }
    }
    return 0.0;
  }
};

// Orientation of c relative to the directed line a->b in the xy-plane (twice the signed area).
inline double orient2d(const Vec3& a, const Vec3& b, const Vec3& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

// orient2d, but 0 where c lies on the line a-b to within 1e-12 of |b - a| |c - a|.
inline double orient2d_snapped(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double o = orient2d(a, b, c);
  const double bx = b[0] - a[0], by = b[1] - a[1], cx = c[0] - a[0], cy = c[1] - a[1];
  return o * o <= 1e-24 * (bx * bx + by * by) * (cx * cx + cy * cy) ? 0.0 : o;
}

// True when bond p-q crosses crack segment a-b in the xy-plane. The bond endpoints must lie on
// opposite sides strictly (a node exactly on the crack line keeps its bonds); a crack end that
// touches the bond counts as crossing.
// Snapped (the crack memory's facets): orientations within round-off of zero count as zero, and
// a facet's end that only touches the bond does not cut it. Facets sit on the lattice by
// construction, their ends often exactly on a child's bond, where the computed sign is round-off:
// mirror images (coordinates differing in their last bits) decided differently, and a
// mirror-symmetric plate cracked on one side only. A facet is a short mark across a broken bond,
// not the crack's extent, so a touch is no crossing. A deck's pre-crack keeps its sides exact
// (a node within round-off of its line is refused at set-up) and snaps only the touch of its
// ends: a bond through a crack end was decided by round-off, differently for p->q and q->p (one
// direction of the pair cut, the other not: unequal forces at the tip) and for mirror images.
template <bool Snapped = false>
inline bool bond_crosses_segment(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b) {
  auto orient = [](const Vec3& u, const Vec3& v, const Vec3& w) {
    return Snapped ? orient2d_snapped(u, v, w) : orient2d(u, v, w);
  };
  const double o1 = orient(a, b, p), o2 = orient(a, b, q);
  if (!((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0))) return false;
  const double o3 = orient2d_snapped(p, q, a), o4 = orient2d_snapped(p, q, b);
  return Snapped ? o3 * o4 < 0 : o3 * o4 <= 0;
}

// True when bond p-q crosses the planar quadrilateral v0..v3 (3D pre-crack). Same conventions as
// the segment test: endpoints strictly on opposite sides of the plane; the quad edge counts.
// Snapped: as for the segment, a side within round-off of the plane counts as on it.
template <bool Snapped = false>
inline bool bond_crosses_quad(const Vec3& p, const Vec3& q, const std::array<Vec3, 4>& v) {
  Vec3 n = cross(sub(v[1], v[0]), sub(v[3], v[0]));
  auto side = [&](const Vec3& x) {
    const Vec3 r = sub(x, v[0]);
    const double d = dot(n, r);
    return Snapped && d * d <= 1e-24 * dot(n, n) * dot(r, r) ? 0.0 : d;
  };
  const double dp = side(p), dq = side(q);
  if (!((dp > 0 && dq < 0) || (dp < 0 && dq > 0))) return false;
  double t = dp / (dp - dq);
  Vec3 x = add(p, scale(sub(q, p), t));
  // Point-in-convex-polygon: x must be on the same side of every edge (or on it).
  double sign = 0;
  for (int e = 0; e < 4; ++e) {
    const Vec3& a = v[e];
    const Vec3& b = v[(e + 1) % 4];
    double s = dot(n, cross(sub(b, a), sub(x, a)));
    double scale_ref = norm(n) * norm(sub(b, a)) * 1e-12;
    if (std::abs(s) <= scale_ref) continue;
    if (sign == 0) sign = s;
    else if ((s > 0) != (sign > 0)) return false;
  }
  return true;
}

}  // namespace periadapt
