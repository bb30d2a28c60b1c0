#include "adapt/refine.hpp"

#include "adapt/crack_memory.hpp"
#include "adapt/boundary_fill.hpp"
#include "adapt/refine_common.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "analysis/energy.hpp"
#include "core/cell_grid.hpp"
#include "core/geometry.hpp"
#include "discretize/lattice_moment.hpp"
#include "discretize/surface_correction.hpp"
#include "material/force_model.hpp"
#include "material/micromodulus.hpp"

namespace periadapt {

double level_horizon(const Model& m, const AdaptSpec& spec, int level) {
  const double h = m.grid_spacing / std::ldexp(1.0, level);
  switch (spec.scaling) {
    case HorizonScaling::Delta: return m.horizon / std::ldexp(1.0, level);
    case HorizonScaling::M: return m.horizon;
    case HorizonScaling::DeltaM: return spec.m_per_level.at(static_cast<std::size_t>(level)) * h;
  }
  return m.horizon;
}

double micromodulus_factor(const Model& m, double m_level) {
  if (!m.material.lattice_calibration) return 1.0;
  return 1.0 / lattice_bond_moment(m.quadrature.rule, m.nodes.dim, m.material.shape, m_level);
}

std::vector<double> level_micromodulus_factors(const Model& m, const AdaptSpec& spec) {
  std::vector<double> f(static_cast<std::size_t>(spec.max_level) + 1, 1.0);
  if (m.material.lattice_calibration)
    for (int l = 0; l <= spec.max_level; ++l)
      f[static_cast<std::size_t>(l)] =
          micromodulus_factor(m, level_horizon(m, spec, l) / (m.grid_spacing / std::ldexp(1.0, l)));
  return f;
}

void scale_material_to_horizon(Model& m, std::size_t i, double factor, double failure_horizon) {
  const MaterialLaw& mat = node_material(m, i);
  NodeSet& ns = m.nodes;
  const double d = ns.horizon[i];
  auto c0_at = [&](double h) {
    return micromodulus_c0(ns.dim, mat.plane, mat.shape, mat.bb_equivalent_E, h, mat.thickness);
  };
  const double c0 = c0_at(d);
  ns.micromodulus[i] = c0 * factor;
  const double df = failure_horizon > 0 ? failure_horizon : d;
  // The breaking stretch is the analytic one: calibration changes the stiffness, not the strain
  // at which a bond fails.
  if (mat.G0 > 0)
    ns.critical_stretch[i] = breaking_stretch(m.formulation, ns.dim, mat, df == d ? c0 : c0_at(df), df);
  else if (std::isfinite(mat.s0))
    // s0 given directly: keep the fracture energy it implies at the base horizon (s0 ~ delta^-1/2).
    ns.critical_stretch[i] = mat.s0 * std::sqrt(m.horizon / df);
  else
    ns.critical_stretch[i] = mat.s0;
}

double failure_horizon(const Model& m, const AdaptSpec& spec, std::size_t i) {
  const NodeSet& ns = m.nodes;
  return (spec.interface_horizon && spec.interface_level_stretch && ns.level[i] > 0)
             ? level_horizon(m, spec, ns.level[i])
             : ns.horizon[i];
}

RefineStats refine_nodes(Model& m, std::vector<std::uint32_t> parents, const AdaptSpec& spec,
                         bool inherit_boundary) {
  if (spec.method == NodeGeneration::A)
    return refine_nodes_method_a(m, std::move(parents), spec, inherit_boundary);
  const auto t0 = std::chrono::steady_clock::now();
  RefineStats st;
  NodeSet& ns = m.nodes;
  BondFamilies& bf = m.bonds;
  const int D = ns.dim;
  const std::vector<char> is_parent = begin_refinement(m, parents, st);
  if (parents.empty()) return st;
  const std::size_t n0 = ns.size();

  const CrackMemory memory = remember_cracks(m, is_parent);

  // Children: offsets +-h/4 along the (possibly rotated) lattice axes.
  const int nchild = 1 << D;
  // Every parent's field gradients first, on the grid as it was: fitted while earlier parents
  // were already switched off, a parent's fit would depend on the processing order (and a
  // mirror-symmetric problem would be refined asymmetrically).
  struct Gradients {
    double g[3][3][3];  // field (u, v, a) -> component -> direction
  };
  std::vector<Gradients> gradients(parents.size());
  for (std::size_t k = 0; k < parents.size(); ++k)
    fit_kinematic_gradients(ns, bf, parents[k], gradients[k].g);
  // Children and their u, v, a, all read from the grid as it was. A child on the far side of a
  // crack from its parent (a rotated lattice puts sub-cells across a pre-crack line; a run-time
  // crack can pass through a cell) takes its field from the nearest old node it can see, with
  // that node's own gradient: anchored at the parent it would get the other crack face's
  // displacement and tear its new bonds apart (thesis 3.2.4: interpolate from visible nodes).
  struct Child {
    std::uint32_t parent;
    Vec3 pos;
    double u[3], v[3], a[3];
    bool reanchored;
    bool filler;  // in an empty cell next to the parent (adapt/boundary_fill.hpp)
  };
  const BoundaryFill fill = boundary_fillers(m, spec, memory, parents, is_parent);
  std::size_t next_filler = 0;
  std::vector<Child> kids;
  kids.reserve(parents.size() * static_cast<std::size_t>(nchild));
  std::vector<std::size_t> first_kid(parents.size() + 1, 0);
  for (std::size_t pk = 0; pk < parents.size(); ++pk) {
    first_kid[pk] = kids.size();
    const std::uint32_t p = parents[pk];
    const auto& G = gradients[pk].g;
    const double h = ns.spacing[p];
    const Vec3 xp{ns.x[0][p], ns.x[1][p], ns.x[2][p]};
    // Sub-cell centres inside the body (a boundary cell of a node-on-edge grid keeps only its
    // inner half or quarter); the parent's volume is shared equally among them, but for
    // boundary cells that fill their empty neighbours (a fine cell's volume each, below).
    std::vector<std::array<double, 3>> offs;
    for (int c = 0; c < nchild; ++c) {
      const std::array<double, 3> off = sub_cell_offset(m, c, h);
      const Vec3 pos{xp[0] + off[0], xp[1] + off[1], xp[2] + off[2]};
      if (inside_body(m, pos, h)) offs.push_back(off);
    }
    // Children's mean offset: the interpolation is anchored there so that momentum is kept.
    double mean[3] = {0, 0, 0};
    for (const auto& o : offs)
      for (int d = 0; d < D; ++d) mean[d] += o[static_cast<std::size_t>(d)] / offs.size();
    for (const auto& off : offs) {
      Child c{p, {xp[0] + off[0], xp[1] + off[1], xp[2] + off[2]}, {}, {}, {}, false, false};
      double de[3] = {0, 0, 0};
      for (int e = 0; e < D; ++e) de[e] = off[static_cast<std::size_t>(e)] - mean[e];
      c.reanchored = interpolate_new_node(m, memory, p, G, de, c.pos, c.u, c.v, c.a);
      st.reanchored += c.reanchored;
      kids.push_back(c);
    }
    for (; next_filler < fill.fillers.size() && fill.fillers[next_filler].parent == p; ++next_filler) {
      const BoundaryFiller& f = fill.fillers[next_filler];
      Child c{p, f.pos, {}, {}, {}, false, true};
      for (int d = 0; d < 3; ++d) c.u[d] = f.u[d], c.v[d] = f.v[d], c.a[d] = f.a[d];
      ++st.fillers;
      kids.push_back(c);
    }
  }
  first_kid[parents.size()] = kids.size();

  const std::vector<double> level_factor = level_micromodulus_factors(m, spec);
  std::vector<char> is_filler;  // per appended node
  // What the fine grid's volumes change in the momentum: the fillers' own, less what a boundary
  // parent's cell had outside the body (at the parent's velocity).
  double P_gained[3] = {0, 0, 0};
  for (std::size_t pk = 0; pk < parents.size(); ++pk) {
    const std::uint32_t p = parents[pk];
    std::size_t nk = 0;  // the parent's own sub-cells, which share its volume
    for (std::size_t c = first_kid[pk]; c < first_kid[pk + 1]; ++c) nk += !kids[c].filler;
    if (nk == 0) continue;  // cannot happen for a node inside the body; keep the parent
    const double h = ns.spacing[p];
    const int level = ns.level[p] + 1;
    const double factor = level_factor.at(static_cast<std::size_t>(level));
    for (std::size_t c = first_kid[pk]; c < first_kid[pk + 1]; ++c) {
      const Child& kid = kids[c];
      // A boundary parent's children and fillers take a fine cell's volume, as on the fine grid
      // (mass the coarse cell had outside the body goes, the fillers' comes); the others share
      // the parent's.
      const double vol = ns.volume[p] / static_cast<double>(fill.boundary_parent[p] ? nchild : nk);
      const std::size_t q = ns.append(kid.pos, vol, 0.5 * h);
      is_filler.push_back(kid.filler);
      ns.level[q] = static_cast<std::int8_t>(level);
      ns.parent[q] = static_cast<std::int32_t>(p);
      ns.density[q] = ns.density[p];
      if (!ns.block.empty()) ns.block[q] = ns.block[p];
      ns.flags[q] = static_cast<std::uint8_t>(kActive | (ns.flags[p] & kNoFail));
      for (int d = 0; d < D; ++d) {
        ns.u[d][q] = kid.u[d];
        ns.v[d][q] = kid.v[d];
        ns.a[d][q] = kid.a[d];
      }
      ns.horizon[q] = level_horizon(m, spec, level);
      scale_material_to_horizon(m, q, factor);
      ns.sync_current(q);
    }
    ns.flags[p] = static_cast<std::uint8_t>(ns.flags[p] & ~kActive);
    if (fill.boundary_parent[p]) {
      const double lost = ns.density[p] * ns.volume[p] * (1.0 - static_cast<double>(nk) / nchild);
      for (int d = 0; d < D; ++d) P_gained[d] -= lost * ns.v[d][p];
    }
    for (int d = 0; d < 3; ++d) ns.v[d][p] = ns.a[d][p] = ns.f[d][p] = 0.0;
    ++st.parents;
    st.children += first_kid[pk + 1] - first_kid[pk];
  }
  // Re-anchored children carry the other face's velocity, so the parents' momentum is not
  // reproduced exactly: a uniform velocity shift of all new nodes restores it (as in method A).
  // Fillers are mass the coarse grid did not have, moving with the body: their own momentum is
  // added, not taken from the others (and a boundary parent's mass outside the body leaves with
  // its own).
  if (st.reanchored > 0) {
    // Exact sums of each rank's own nodes (analysis/energy.hpp): the serial run's bits.
    const std::array<double, 3> P =
        momentum_and_kinetic(ns, m.partition.active ? &m.partition : nullptr).momentum;
    double M = 0;
    for (std::size_t i = n0; i < ns.size(); ++i) {
      if (!(ns.flags[i] & kActive)) continue;
      const double mi = ns.density[i] * ns.volume[i];
      M += mi;
      if (is_filler[i - n0])
        for (int d = 0; d < D; ++d) P_gained[d] += mi * ns.v[d][i];
    }
    for (std::size_t q = n0; q < ns.size(); ++q)
      for (int d = 0; d < D; ++d) ns.v[d][q] += (st.momentum_before[d] + P_gained[d] - P[d]) / M;
  }

  if (inherit_boundary) inherit_loads_and_motions(m, n0, is_parent, false);

  std::vector<char> changed(ns.size(), 0);
  for (std::size_t i = 0; i < n0; ++i) changed[i] = is_parent[i];
  finish_refinement(m, spec, memory, n0, changed, t0, st);
  return st;
}

}  // namespace periadapt

namespace periadapt {

void apply_initial_refinement(Model& m, const AdaptSpec& spec) {
  const NodeSet& ns = m.nodes;
  int top = 0;
  for (const auto& z : spec.initial) top = std::max(top, z.level);
  for (int level = 0; level < top; ++level) {
    std::vector<char> want(ns.size(), 0);
    std::vector<std::uint32_t> ids;
    std::vector<const Shape*> within;  // per id: where its visibility may reach (null: anywhere)
    std::vector<char> widen;   // per id: whether its zone is widened
    for (std::size_t i = 0; i < ns.size(); ++i) {
      if (!(ns.flags[i] & kActive) || ns.level[i] != level) continue;
      const Vec3 p{ns.x[0][i], ns.x[1][i], ns.x[2][i]};
      for (const auto& z : spec.initial)
        if (z.level > level && z.region.contains(p, 1e-9 * ns.spacing[i]) &&
            (!z.within || z.within->contains(p, 1e-9 * ns.spacing[i]))) {
          ids.push_back(static_cast<std::uint32_t>(i));
          within.push_back(z.within ? &*z.within : nullptr);
          widen.push_back(z.widen);
          break;
        }
    }
    if (ids.empty()) continue;
    // Visibility: whatever sees an identified node at its level is refined too.
    std::vector<std::uint32_t> parents = ids;
    {
      double hmax = 0;
      for (std::uint32_t i : ids) hmax = std::max(hmax, ns.horizon[i]);
      CellGrid grid(ns.dim, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()}, ns.size(), hmax);
      std::vector<char> mark(ns.size(), 0);
      for (std::uint32_t i : ids) mark[i] = 1;
      // Nodes with prescribed motions are pulled in only when inside a zone themselves.
      if (spec.visibility)
        for (std::size_t r = 0; r < ids.size(); ++r) {
          const std::uint32_t i = ids[r];
          if (!widen[r]) continue;
          grid.for_each_within({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, ns.horizon[i] * (1 + 1e-12),
                               [&](std::uint32_t j, double) {
                                 if ((ns.flags[j] & kActive) && !(ns.flags[j] & kBoundary) &&
                                     ns.level[j] <= level &&
                                     (!within[r] || within[r]->contains({ns.x[0][j], ns.x[1][j], ns.x[2][j]},
                                                                        1e-9 * ns.spacing[j])))
                                   mark[j] = 1;
                               });
        }
      parents.clear();
      for (std::size_t i = 0; i < ns.size(); ++i)
        if (mark[i]) parents.push_back(static_cast<std::uint32_t>(i));
    }
    refine_nodes(m, parents, spec, true);
  }
}

}  // namespace periadapt
