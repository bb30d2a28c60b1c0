#include "adapt/boundary_fill.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "adapt/refine_common.hpp"
#include "core/geometry.hpp"

namespace periadapt {

namespace {

// The 3^dim cells around a cell (the cell itself included, at q = 3^dim / 2): offset q.
int fill_neighbour_count(int D) { return D == 1 ? 3 : D == 2 ? 9 : 27; }

void fill_offset_of(int D, int q, int k[3]) {
  k[0] = q % 3 - 1;
  k[1] = D > 1 ? (q / 3) % 3 - 1 : 0;
  k[2] = D > 2 ? q / 9 - 1 : 0;
}

bool fill_is_centre(const int k[3]) { return k[0] == 0 && k[1] == 0 && k[2] == 0; }

Vec3 fill_plus(const Vec3& x, const Vec3& d) { return {x[0] + d[0], x[1] + d[1], x[2] + d[2]}; }

}  // namespace

Vec3 lattice_offset(const Model& m, const int k[3], double h) {
  const int D = m.nodes.dim;
  const double ox = k[0] * h, oy = D > 1 ? k[1] * h : 0.0;
  if (D != 2) return {ox, oy, D > 2 ? k[2] * h : 0.0};
  const double cr = std::cos(m.lattice_rotation), sr = std::sin(m.lattice_rotation);
  return {cr * ox - sr * oy, sr * ox + cr * oy, 0.0};
}

std::array<double, 3> sub_cell_offset(const Model& m, int c, double h) {
  const int D = m.nodes.dim;
  std::array<double, 3> off{0, 0, 0};
  for (int d = 0; d < D; ++d) off[d] = ((c >> d) & 1 ? 0.25 : -0.25) * h;
  if (D == 2) {
    const double cr = std::cos(m.lattice_rotation), sr = std::sin(m.lattice_rotation);
    const double ox = off[0], oy = off[1];
    off[0] = cr * ox - sr * oy;
    off[1] = sr * ox + cr * oy;
  }
  return off;
}

BoundaryFill boundary_fillers(const Model& m, const AdaptSpec& spec, const CrackMemory& memory,
                              const std::vector<std::uint32_t>& parents,
                              const std::vector<char>& is_parent) {
  const NodeSet& ns = m.nodes;
  const BondFamilies& bf = m.bonds;
  const int D = ns.dim, nneigh = fill_neighbour_count(D), nchild = 1 << D;
  BoundaryFill out;
  out.boundary_parent.assign(ns.size(), 0);
  if (!spec.fill_boundary_cells || spec.method != NodeGeneration::B ||
      (m.holes.empty() && !m.body_clip && m.lattice_rotation == 0.0))
    return out;
  auto cell_at = [&](const Vec3& x, const int k[3], double h) { return fill_plus(x, lattice_offset(m, k, h)); };

  // Parents with an empty cell next to them.
  std::vector<char> carries(ns.size(), 0);
  for (const BodyLoad& l : m.loads)
    for (std::uint32_t i : l.nodes) carries[i] = 1;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.flags[i] & kBoundary) carries[i] = 1;
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  bool any = false;
  for (std::uint32_t p : parents) {
    if (carries[p]) continue;
    const Vec3 xp{ns.x[0][p], ns.x[1][p], ns.x[2][p]};
    bool empty = false;
    for (int q = 0; q < nneigh && !empty; ++q) {
      int n[3];
      fill_offset_of(D, q, n);
      empty = !fill_is_centre(n) && !inside_body(m, cell_at(xp, n, ns.spacing[p]), ns.spacing[p]);
    }
    if (!empty) continue;
    out.boundary_parent[p] = 1;
    any = true;
    for (int d = 0; d < D; ++d) {
      lo[d] = std::min(lo[d], xp[d] - 2.5 * ns.spacing[p]);
      hi[d] = std::max(hi[d], xp[d] + 2.5 * ns.spacing[p]);
    }
  }
  if (!any) return out;

  // The nodes around them by level and lattice position (a refined node keeps its slot and so
  // its place; coarsening retires children for good): whether a filler exists already, and
  // whether the cells around an empty one are refined. The quantum is finer than every lattice
  // a node can sit on.
  const double quantum = m.grid_spacing / std::ldexp(1.0, spec.max_level + 3);
  using Key = std::array<long long, 4>;
  auto key_of = [&](int level, const Vec3& x) {
    Key k{level, 0, 0, 0};
    for (int d = 0; d < D; ++d) k[static_cast<std::size_t>(d) + 1] = std::llround(x[d] / quantum);
    return k;
  };
  std::map<Key, std::uint32_t> placed;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    const bool retired = !(ns.flags[i] & kActive) && ns.level[i] > 0 && ns.parent[i] < 0;
    bool near = !retired;
    for (int d = 0; d < D && near; ++d) near = ns.x[d][i] >= lo[d] && ns.x[d][i] <= hi[d];
    if (near) placed.emplace(key_of(ns.level[i], {ns.x[0][i], ns.x[1][i], ns.x[2][i]}),
                             static_cast<std::uint32_t>(i));
  }

  std::set<Key> cells_done;  // empty cells this event has looked at
  for (std::uint32_t p : parents) {
    if (!out.boundary_parent[p]) continue;
    const double h = ns.spacing[p];
    const int level = ns.level[p];
    const Vec3 xp{ns.x[0][p], ns.x[1][p], ns.x[2][p]};
    for (int q = 0; q < nneigh; ++q) {
      int n[3];
      fill_offset_of(D, q, n);
      if (fill_is_centre(n)) continue;
      const Vec3 vc = cell_at(xp, n, h);
      if (inside_body(m, vc, h) || !cells_done.insert(key_of(level, vc)).second) continue;
      bool surrounded = true;
      for (int r = 0; r < nneigh && surrounded; ++r) {
        int k[3];
        fill_offset_of(D, r, k);
        if (fill_is_centre(k)) continue;
        const Vec3 cc = cell_at(vc, k, h);
        if (!inside_body(m, cc, h)) continue;
        const auto it = placed.find(key_of(level, cc));
        surrounded = it != placed.end() &&
                     (is_parent[it->second] || !(ns.flags[it->second] & kActive));
      }
      if (!surrounded) continue;
      for (int c = 0; c < nchild; ++c) {
        const auto off = sub_cell_offset(m, c, h);
        const Vec3 o = fill_plus(vc, {off[0], off[1], off[2]});
        if (!inside_body(m, o, h) || placed.count(key_of(level + 1, o))) continue;
        // Its field: from the nearest nodes that can see it, among the parent and its family.
        std::vector<std::uint32_t> candidates{p};
        candidates.insert(candidates.end(), bf.neighbor.begin() + static_cast<std::ptrdiff_t>(bf.begin(p)),
                          bf.neighbor.begin() + static_cast<std::ptrdiff_t>(bf.end(p)));
        BoundaryFiller f{p, o, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        if (!extrapolate_from_nearest_visible(m, memory, candidates, o, f.u, f.v, f.a)) continue;
        out.fillers.push_back(f);
      }
    }
  }
  return out;
}

}  // namespace periadapt
