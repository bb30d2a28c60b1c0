#include "discretize/precrack.hpp"

#include <algorithm>
#include <cmath>

namespace periadapt {

std::size_t apply_precracks(const NodeSet& nodes, BondFamilies& bonds,
                            const std::vector<PreCrack>& cracks, const std::vector<char>* rows,
                            std::vector<std::size_t>* per_crack) {
  std::size_t total = 0;
  const std::size_t n = nodes.size();
  if (per_crack) per_crack->assign(cracks.size(), 0);
  for (std::size_t ci = 0; ci < cracks.size(); ++ci) {
    const PreCrack& c = cracks[ci];
    std::size_t cut = 0;
    // Only nodes within one horizon of the crack's bounding box can own a crossing bond.
    Box bb;
    const int np = c.planar3d ? 4 : 2;
    for (int d = 0; d < 3; ++d) {
      bb.lo[d] = bb.hi[d] = c.points[0][d];
      for (int k = 1; k < np; ++k) {
        bb.lo[d] = std::min(bb.lo[d], c.points[k][d]);
        bb.hi[d] = std::max(bb.hi[d], c.points[k][d]);
      }
    }
#pragma omp parallel for schedule(static) reduction(+ : cut)
    for (std::size_t i = 0; i < n; ++i) {
      if (rows && !(i < rows->size() && (*rows)[i])) continue;
      const Vec3 p{nodes.x[0][i], nodes.x[1][i], nodes.x[2][i]};
      const double h = nodes.horizon[i];
      bool near = true;
      for (int d = 0; d < nodes.dim; ++d)
        if (p[d] < bb.lo[d] - h || p[d] > bb.hi[d] + h) near = false;
      if (!near) continue;
      for (std::uint64_t k = bonds.begin(i); k < bonds.end(i); ++k) {
        if (!BondFamilies::intact(bonds.beta[k])) continue;
        const std::uint32_t j = bonds.neighbor[k];
        const Vec3 q{nodes.x[0][j], nodes.x[1][j], nodes.x[2][j]};
        const bool crosses = c.planar3d ? bond_crosses_quad(p, q, c.points)
                                        : bond_crosses_segment(p, q, c.points[0], c.points[1]);
        if (crosses) {
          bonds.beta[k] = -bonds.beta[k];
          ++cut;
        }
      }
    }
    if (per_crack) (*per_crack)[ci] = cut;
    total += cut;
  }
  return total;
}

namespace {

bool on_crack(const PreCrack& c, const Vec3& p, double tol) {
  if (!c.planar3d) {
    const Vec3 &a = c.points[0], &b = c.points[1];
    const double bx = b[0] - a[0], by = b[1] - a[1], len = std::hypot(bx, by);
    if (!(len > 0)) return false;
    const double t = ((p[0] - a[0]) * bx + (p[1] - a[1]) * by) / len;  // along, in metres
    return std::abs(orient2d(a, b, p)) / len <= tol && t > tol && t < len - tol;
  }
  const auto& v = c.points;
  const Vec3 n = cross(sub(v[1], v[0]), sub(v[3], v[0]));
  const double nn = norm(n);
  if (!(nn > 0) || std::abs(dot(n, sub(p, v[0]))) / nn > tol) return false;
  double sign = 0;  // strictly inside every edge
  for (int e = 0; e < 4; ++e) {
    const Vec3 &a = v[e], &b = v[(e + 1) % 4];
    const double s = dot(n, cross(sub(b, a), sub(p, a))) / (nn * norm(sub(b, a)));
    if (std::abs(s) <= tol) return false;
    if (sign == 0) sign = s;
    else if ((s > 0) != (sign > 0)) return false;
  }
  return true;
}

// Distance from p to the crack's line or plane (an upper bound is not needed: a cell farther
// than its half-diagonal holds no point on the crack).
double distance_to_crack_carrier(const PreCrack& c, const Vec3& p) {
  if (!c.planar3d) {
    const Vec3 &a = c.points[0], &b = c.points[1];
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    return len > 0 ? std::abs(orient2d(a, b, p)) / len : INFINITY;
  }
  const Vec3 n = cross(sub(c.points[1], c.points[0]), sub(c.points[3], c.points[0]));
  const double nn = norm(n);
  return nn > 0 ? std::abs(dot(n, sub(p, c.points[0]))) / nn : INFINITY;
}

}  // namespace

std::size_t points_on_precrack(const NodeSet& nodes, const PreCrack& c, int levels,
                               const ChildLattice& lattice, int* level, Vec3* first) {
  const int D = nodes.dim;
  const double cr = std::cos(lattice.rotation), sr = std::sin(lattice.rotation);
  for (int l = 0; l <= levels; ++l) {
    const int per = 1 << l;  // sub-cells per cell edge
    // Offsets along each lattice axis, in cell spacings: method B's sub-cell centres; method A's
    // lattice of spacing 1 / per through the node, its cell's edges included (shared with the
    // neighbouring cell: the points found are made unique below).
    std::vector<double> axis;
    if (l == 0)
      axis = {0.0};
    else if (lattice.method_a)
      for (int j = -per / 2; j <= per / 2; ++j) axis.push_back(static_cast<double>(j) / per);
    else
      for (int j = 0; j < per; ++j) axis.push_back(-0.5 + (2.0 * j + 1.0) / (2.0 * per));
    const int na = static_cast<int>(axis.size());
    std::vector<Vec3> found;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      if (!(nodes.flags[i] & kActive)) continue;
      const Vec3 p{nodes.x[0][i], nodes.x[1][i], nodes.x[2][i]};
      const double h = nodes.spacing[i];
      if (l > 0 && distance_to_crack_carrier(c, p) > 0.5 * h * std::sqrt(double(D)) * (1 + 1e-9)) continue;
      const double tol = 1e-9 * h / per;
      int k[3] = {0, 0, 0};
      for (;;) {
        double off[3] = {0, 0, 0};
        for (int d = 0; d < D; ++d) off[d] = h * axis[static_cast<std::size_t>(k[d])];
        if (D == 2) {
          const double ox = off[0], oy = off[1];
          off[0] = cr * ox - sr * oy;
          off[1] = sr * ox + cr * oy;
        }
        const Vec3 q{p[0] + off[0], p[1] + off[1], p[2] + off[2]};
        if (on_crack(c, q, tol)) found.push_back(q);
        int d = 0;
        while (d < D && ++k[d] == na) k[d++] = 0;
        if (d == D) break;
      }
    }
    if (lattice.method_a && l > 0) {
      // A point on an edge between two cells is found from both: count it once.
      const double h0 = nodes.size() ? nodes.spacing[0] : 1.0;
      const double q = 1e-6 * h0 / per;
      auto key = [&](const Vec3& v) {
        return std::array<long long, 3>{std::llround(v[0] / q), std::llround(v[1] / q), std::llround(v[2] / q)};
      };
      std::sort(found.begin(), found.end(), [&](const Vec3& x, const Vec3& y) { return key(x) < key(y); });
      found.erase(std::unique(found.begin(), found.end(),
                              [&](const Vec3& x, const Vec3& y) { return key(x) == key(y); }),
                  found.end());
    }
    if (!found.empty()) {
      if (level) *level = l;
      if (first) *first = found.front();
      return found.size();
    }
  }
  return 0;
}

}  // namespace periadapt
