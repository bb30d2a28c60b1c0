#include "adapt/refine_common.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/energy.hpp"
#include "core/cell_grid.hpp"
#include "core/visible_gradient.hpp"
#include "discretize/families.hpp"
#include "parallel/held_rows.hpp"

namespace periadapt {

std::vector<char> begin_refinement(Model& m, std::vector<std::uint32_t>& parents, RefineStats& st) {
  std::sort(parents.begin(), parents.end());
  parents.erase(std::unique(parents.begin(), parents.end()), parents.end());
  if (parents.empty()) return {};
  const MomentumAndKinetic pk = momentum_and_kinetic(m.nodes, m.partition.active ? &m.partition : nullptr);
  st.momentum_before = pk.momentum;
  st.kinetic_before = pk.kinetic;
  st.momentum_scale = pk.momentum_scale;
  std::vector<char> is_parent(m.nodes.size(), 0);
  for (std::uint32_t p : parents) is_parent[p] = 1;
  if (m.partition.rows_held) {
    // The gradient fits and the crack memory read the parents' rows and their neighbours'.
    publish_rows(m.partition, m.bonds, parents);
    std::vector<char> near(m.nodes.size(), 0);
    for (std::uint32_t p : parents)
      for (std::uint64_t k = m.bonds.begin(p); k < m.bonds.end(p); ++k) near[m.bonds.neighbor[k]] = 1;
    std::vector<std::uint32_t> rows;
    for (std::size_t i = 0; i < near.size(); ++i)
      if (near[i] && !is_parent[i]) rows.push_back(static_cast<std::uint32_t>(i));
    publish_rows(m.partition, m.bonds, rows);
  }
  return is_parent;
}

bool inside_body(const Model& m, const Vec3& pos, double h) {
  if (!m.body.contains(pos, 1e-9 * h)) return false;
  for (const Shape& hole : m.holes)
    if (hole.contains(pos, 0.0)) return false;
  return !m.body_clip || m.body_clip->contains(pos, 1e-9 * h);
}

bool sight_blocked(const Model& m, const CrackMemory& memory, const Vec3& a, const Vec3& b) {
  for (const PreCrack& c : m.cracks) {
    const bool crosses = c.planar3d ? bond_crosses_quad(a, b, c.points)
                                    : bond_crosses_segment(a, b, c.points[0], c.points[1]);
    if (crosses) return true;
  }
  const double len = norm(sub(b, a));
  for (const Facet& f : memory.facets)
    if (norm(sub(f.centre(), a)) <= f.reach() + len && f.crossed_by(a, b)) return true;
  return false;
}

void fit_kinematic_gradients(const NodeSet& ns, const BondFamilies& bf, std::uint32_t p,
                             double G[3][3][3]) {
  fit_gradient(ns, bf, p, ns.u, G[0]);
  fit_gradient(ns, bf, p, ns.v, G[1]);
  fit_gradient(ns, bf, p, ns.a, G[2]);
}

namespace {

// Adds node j's u, v, a extrapolated by its gradients G over `off` to u, v, a.
void add_extrapolation(const NodeSet& ns, std::uint32_t j, const double G[3][3][3],
                       const double off[3], double u[3], double v[3], double a[3]) {
  for (int d = 0; d < 3; ++d) {
    double du = 0, dv = 0, da = 0;
    for (int e = 0; e < ns.dim; ++e) {
      du += G[0][d][e] * off[e];
      dv += G[1][d][e] * off[e];
      da += G[2][d][e] * off[e];
    }
    u[d] += ns.u[d][j] + du;
    v[d] += ns.v[d][j] + dv;
    a[d] += ns.a[d][j] + da;
  }
}

}  // namespace

bool extrapolate_from_nearest_visible(const Model& m, const CrackMemory& memory,
                                      const std::vector<std::uint32_t>& candidates, const Vec3& pos,
                                      double u[3], double v[3], double a[3]) {
  const NodeSet& ns = m.nodes;
  for (int d = 0; d < 3; ++d) u[d] = v[d] = a[d] = 0;
  std::vector<std::pair<double, std::uint32_t>> seen;
  for (std::uint32_t j : candidates) {
    if (!(ns.flags[j] & kActive)) continue;
    const Vec3 xj{ns.x[0][j], ns.x[1][j], ns.x[2][j]};
    if (!sight_blocked(m, memory, xj, pos)) seen.emplace_back(norm(sub(xj, pos)), j);
  }
  if (seen.empty()) return false;
  double best = INFINITY;
  for (const auto& s : seen) best = std::min(best, s.first);
  int count = 0;
  for (const auto& [dist, j] : seen) {
    if (dist > best * (1 + 1e-9)) continue;
    double Gj[3][3][3];
    fit_kinematic_gradients(ns, m.bonds, j, Gj);
    double off[3] = {0, 0, 0};
    for (int e = 0; e < ns.dim; ++e) off[e] = pos[static_cast<std::size_t>(e)] - ns.x[e][j];
    add_extrapolation(ns, j, Gj, off, u, v, a);
    ++count;
  }
  for (int d = 0; d < 3; ++d) u[d] /= count, v[d] /= count, a[d] /= count;
  return true;
}

bool interpolate_new_node(const Model& m, const CrackMemory& memory, std::uint32_t p,
                          const double G[3][3][3], const double offset[3], const Vec3& pos,
                          double u[3], double v[3], double a[3]) {
  const NodeSet& ns = m.nodes;
  const BondFamilies& bf = m.bonds;
  const Vec3 xp{ns.x[0][p], ns.x[1][p], ns.x[2][p]};
  // Hidden from its parent: the nearest old nodes of the parent's family it can see.
  if (sight_blocked(m, memory, xp, pos)) {
    const std::vector<std::uint32_t> family(bf.neighbor.begin() + static_cast<std::ptrdiff_t>(bf.begin(p)),
                                            bf.neighbor.begin() + static_cast<std::ptrdiff_t>(bf.end(p)));
    if (extrapolate_from_nearest_visible(m, memory, family, pos, u, v, a)) return true;
  }
  for (int d = 0; d < 3; ++d) u[d] = v[d] = a[d] = 0;
  add_extrapolation(ns, p, G, offset, u, v, a);
  return false;
}

void inherit_loads_and_motions(Model& m, std::size_t n0, const std::vector<char>& is_parent,
                               bool parents_survive) {
  NodeSet& ns = m.nodes;
  std::vector<std::vector<std::uint32_t>> children(n0);
  for (std::size_t q = n0; q < ns.size(); ++q)
    if (ns.parent[q] >= 0) children[static_cast<std::size_t>(ns.parent[q])].push_back(static_cast<std::uint32_t>(q));
  auto expand = [&](std::vector<std::uint32_t>& list) {
    std::vector<std::uint32_t> out;
    for (std::uint32_t i : list) {
      const bool refined = i < n0 && is_parent[i] && !children[i].empty();
      if (!refined || parents_survive) out.push_back(i);
      if (refined) out.insert(out.end(), children[i].begin(), children[i].end());
    }
    std::sort(out.begin(), out.end());
    list = std::move(out);
  };
  for (BodyLoad& l : m.loads) expand(l.nodes);
  // Prescribed motions follow their region: a child inside it is constrained, one outside not.
  for (PrescribedMotion& pm : m.motions) {
    expand(pm.nodes);
    const double tol = 1e-9 * m.grid_spacing;
    std::vector<std::uint32_t> kept;
    for (std::uint32_t i : pm.nodes)
      if (i < n0 || pm.region.contains({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, tol))
        kept.push_back(i);
    pm.nodes = std::move(kept);
  }
  for (std::size_t i = n0; i < ns.size(); ++i) ns.flags[i] &= static_cast<std::uint8_t>(~kBoundary);
  for (const PrescribedMotion& pm : m.motions)
    for (std::uint32_t i : pm.nodes) ns.flags[i] |= kBoundary;
}

void finish_refinement(Model& m, const AdaptSpec& spec, const CrackMemory& memory, std::size_t n0,
                       std::vector<char> changed, std::chrono::steady_clock::time_point t0,
                       RefineStats& st) {
  NodeSet& ns = m.nodes;
  const int D = ns.dim;
  std::vector<double> horizon_before(ns.horizon.begin(), ns.horizon.begin() + static_cast<long>(n0));
  // Interface-horizon correction: refined nodes next to a coarser node take m times the
  // distance to it, so their families lose no volume across the interface (thesis Fig. 3.10b).
  if (spec.interface_horizon) {
    double hmax = 0;
    for (std::size_t i = 0; i < ns.size(); ++i)
      if (ns.flags[i] & kActive) hmax = std::max(hmax, ns.spacing[i]);
    // A node's nearest coarser node lies within 2 hmax, so only nodes that near this event's
    // new, deactivated or resized nodes can change. Coarsening changes nodes without passing
    // here, so with it every node is looked at again.
    std::vector<std::uint32_t> rows, near;
    if (spec.coarsen) {
      for (std::size_t i = 0; i < ns.size(); ++i)
        if (ns.flags[i] & kActive) rows.push_back(static_cast<std::uint32_t>(i));
      near = rows;
    } else {
      std::vector<std::uint32_t> seeds;
      for (std::size_t i = 0; i < ns.size(); ++i)
        if (i >= n0 || (i < changed.size() && changed[i])) seeds.push_back(static_cast<std::uint32_t>(i));
      rows = active_nodes_near(ns, seeds, 2 * hmax * (1 + 1e-9));
      near = active_nodes_near(ns, seeds, 4 * hmax * (1 + 1e-9));
    }
    // Cells of the finest spacing among the rows: a query (2 spacings around a fine node) then
    // tests ~25 candidates, not the ~60 of cells sized 2 hmax.
    double smin = hmax;
    for (std::uint32_t i : rows)
      if (ns.level[i] > 0) smin = std::min(smin, ns.spacing[i]);
    const CellGrid grid(D, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()}, near,
                        std::max(smin, 0.25 * hmax));
    const std::vector<double> level_factor = level_micromodulus_factors(m, spec);
    // Rows are independent: each writes only its own horizon and material constants.
#pragma omp parallel for schedule(dynamic, 64)
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const std::uint32_t i = rows[r];
      if (ns.level[i] == 0) continue;
      const double base = level_horizon(m, spec, ns.level[i]);
      const double mi = base / ns.spacing[i];
      double dmin = INFINITY;
      grid.for_each_within({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, 2.0 * ns.spacing[i],
                           [&](std::uint32_t j, double d2) {
                             if ((ns.flags[j] & kActive) && ns.spacing[j] > 1.5 * ns.spacing[i])
                               dmin = std::min(dmin, std::sqrt(d2));
                           });
      const double want = std::isfinite(dmin) ? std::max(base, mi * dmin) : base;
      if (want != ns.horizon[i]) {
        ns.horizon[i] = want;
        scale_material_to_horizon(m, i, level_factor.at(static_cast<std::size_t>(ns.level[i])),
                                  spec.interface_level_stretch ? base : 0.0);
      }
    }
  }

  changed.resize(ns.size(), 0);
  for (std::size_t i = 0; i < ns.size(); ++i)
    changed[i] = changed[i] || i >= n0 ||
                 (i < horizon_before.size() && horizon_before[i] != ns.horizon[i]);
  // Method B switches parents off and appends children; method A also shrinks the parents'
  // spacing, which the rows around them see.
  st.rebuilt = rebuild_families(m, memory, n0, changed, spec.method == NodeGeneration::B);
  const MomentumAndKinetic pk = momentum_and_kinetic(ns, m.partition.active ? &m.partition : nullptr);
  st.momentum_after = pk.momentum;
  st.kinetic_after = pk.kinetic;
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace periadapt
