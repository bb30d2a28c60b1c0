// Node generation method A (thesis 3.2.3, Fig. 3.5a; MSc Eqs. 37-38): a parent of spacing h gets
// the 3^dim lattice of spacing h/2 around it (mid-points towards its neighbours, shared with a
// refined neighbour) and stays, as a node of the finer level; ids never change. Each new node owns
// the cell of side h/2 around it. Where such a cell reaches into the cell of a coarse node that
// is not refined, that node loses the covered volume: an axial fine neighbour takes half a fine
// cell, a diagonal one a quarter, which is Eq. 3.4 (V - V_f/4 ... V - 7 V_f/4 for j = 1 ... 5)
// computed from the geometry, so the total volume is unchanged on any configuration.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "adapt/crack_memory.hpp"
#include "adapt/refine_common.hpp"
#include "analysis/energy.hpp"
#include "core/cell_grid.hpp"

namespace periadapt {

namespace {

struct Candidate {
  Vec3 pos;
  std::uint32_t parent;
  double u[3], v[3], a[3];  // extrapolated from the generating parent
};

}  // namespace

RefineStats refine_nodes_method_a(Model& m, std::vector<std::uint32_t> parents,
                                  const AdaptSpec& spec, bool inherit_boundary) {
  const auto t0 = std::chrono::steady_clock::now();
  RefineStats st;
  NodeSet& ns = m.nodes;
  BondFamilies& bf = m.bonds;
  const int D = ns.dim;
  const std::vector<char> is_parent = begin_refinement(m, parents, st);
  if (parents.empty()) return st;
  const std::size_t n0 = ns.size();
  const CrackMemory memory = remember_cracks(m, std::vector<char>(n0, 0), &is_parent);

  const double cr = std::cos(m.lattice_rotation), sr = std::sin(m.lattice_rotation);
  double hmax = 0, hmin = INFINITY;
  for (std::size_t i = 0; i < n0; ++i)
    if (ns.flags[i] & kActive) hmax = std::max(hmax, ns.spacing[i]);
  for (std::uint32_t p : parents) hmin = std::min(hmin, ns.spacing[p]);
  const double same = 1e-6 * hmin;  // two points this close are one node
  const CellGrid existing(D, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()}, n0, hmax);

  // Candidates: the lattice points around every parent that are inside the body and not a node.
  std::vector<Candidate> cand;
  int counts[3] = {1, 1, 1};
  for (int d = 0; d < D; ++d) counts[d] = 3;
  for (std::uint32_t p : parents) {
    double G[3][3][3];  // field (u, v, a) -> component -> direction
    fit_kinematic_gradients(ns, bf, p, G);
    const double h = ns.spacing[p];
    for (int k = 0; k < counts[2]; ++k)
      for (int j = 0; j < counts[1]; ++j)
        for (int i = 0; i < counts[0]; ++i) {
          const int idx[3] = {i - (D > 0), j - (D > 1), k - (D > 2)};
          if (idx[0] == 0 && idx[1] == 0 && idx[2] == 0) continue;
          double off[3] = {0.5 * h * idx[0], 0.5 * h * idx[1], 0.5 * h * idx[2]};
          if (D == 2) {
            const double ox = off[0], oy = off[1];
            off[0] = cr * ox - sr * oy;
            off[1] = sr * ox + cr * oy;
          }
          const Vec3 pos{ns.x[0][p] + off[0], ns.x[1][p] + off[1], ns.x[2][p] + off[2]};
          if (!inside_body(m, pos, h)) continue;
          bool taken = false;
          existing.for_each_within(pos, same, [&](std::uint32_t q, double) {
            taken = taken || (ns.flags[q] & kActive);
          });
          if (taken) continue;
          Candidate c{pos, p, {}, {}, {}};
          st.reanchored += interpolate_new_node(m, memory, p, G, off, pos, c.u, c.v, c.a);
          cand.push_back(c);
        }
  }
  // A mid-point between two refined parents is generated twice: one node, the mean of the two
  // extrapolations, owned by the lower parent id (candidates come in parent order).
  std::vector<double> cx[3];
  for (int d = 0; d < 3; ++d) {
    cx[d].resize(cand.size());
    for (std::size_t c = 0; c < cand.size(); ++c) cx[d][c] = cand[c].pos[d];
  }
  const CellGrid cgrid(D, {cx[0].data(), cx[1].data(), cx[2].data()}, cand.size(), hmin);
  std::vector<char> merged(cand.size(), 0);
  std::vector<std::uint32_t> created;
  const std::vector<double> level_factor = level_micromodulus_factors(m, spec);
  for (std::size_t c = 0; c < cand.size(); ++c) {
    if (merged[c]) continue;
    Candidate rep = cand[c];
    int n = 1;
    cgrid.for_each_within(cand[c].pos, same, [&](std::uint32_t o, double) {
      if (o <= c || merged[o]) return;
      merged[o] = 1;
      ++n;
      for (int d = 0; d < 3; ++d) {
        rep.u[d] += cand[o].u[d];
        rep.v[d] += cand[o].v[d];
        rep.a[d] += cand[o].a[d];
      }
    });
    const std::uint32_t p = rep.parent;
    const std::size_t q = ns.append(rep.pos, 0.0, 0.5 * ns.spacing[p]);
    ns.level[q] = static_cast<std::int8_t>(ns.level[p] + 1);
    ns.parent[q] = static_cast<std::int32_t>(p);
    ns.density[q] = ns.density[p];
    if (!ns.block.empty()) ns.block[q] = ns.block[p];
    ns.flags[q] = static_cast<std::uint8_t>(kActive | (ns.flags[p] & kNoFail));
    for (int d = 0; d < D; ++d) {
      ns.u[d][q] = rep.u[d] / n;
      ns.v[d][q] = rep.v[d] / n;
      ns.a[d][q] = rep.a[d] / n;
    }
    ns.horizon[q] = level_horizon(m, spec, ns.level[q]);
    scale_material_to_horizon(m, q, level_factor.at(static_cast<std::size_t>(ns.level[q])));
    created.push_back(static_cast<std::uint32_t>(q));
  }
  for (std::uint32_t p : parents) {
    ns.level[p] = static_cast<std::int8_t>(ns.level[p] + 1);
    ns.spacing[p] *= 0.5;
    ns.horizon[p] = level_horizon(m, spec, ns.level[p]);
    scale_material_to_horizon(m, p, level_factor.at(static_cast<std::size_t>(ns.level[p])));
  }

  // Volumes: fine cells clipped to the body box (unrotated lattices; a rotated lattice's cells are
  // kept whole), then the coarse cells they reach into lose the overlap.
  const double measure = D == 1 ? m.material.thickness : D == 2 ? m.material.thickness : 1.0;
  auto cell_volume_of = [&](std::size_t i) {
    double v = measure;
    for (int d = 0; d < D; ++d) {
      const double h = ns.spacing[i], c = ns.x[d][i];
      double lo = c - 0.5 * h, hi = c + 0.5 * h;
      if (m.lattice_rotation == 0.0) lo = std::max(lo, m.body.lo[d]), hi = std::min(hi, m.body.hi[d]);
      v *= std::max(0.0, hi - lo);
    }
    return v;
  };
  for (std::uint32_t p : parents) ns.volume[p] = cell_volume_of(p);
  for (std::uint32_t q : created) ns.volume[q] = cell_volume_of(q);
  std::vector<char> changed(ns.size(), 0);
  for (std::uint32_t p : parents) changed[p] = 1;
  const double reach = std::sqrt(static_cast<double>(D)) * 0.5 * (hmax + hmin);
  // (appending nodes moved the coordinate arrays: a new grid over the old nodes)
  const CellGrid old_nodes(D, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()}, n0, hmax);
  for (std::uint32_t q : created) {
    const double hq = ns.spacing[q];
    old_nodes.for_each_within({ns.x[0][q], ns.x[1][q], ns.x[2][q]}, reach, [&](std::uint32_t j, double) {
      if (!(ns.flags[j] & kActive) || is_parent[j] || !(ns.spacing[j] > 1.5 * hq)) return;
      // Overlap of the two cells in the lattice frame.
      double dl[3] = {ns.x[0][q] - ns.x[0][j], ns.x[1][q] - ns.x[1][j], ns.x[2][q] - ns.x[2][j]};
      if (D == 2) {
        const double lx = cr * dl[0] + sr * dl[1], ly = -sr * dl[0] + cr * dl[1];
        dl[0] = lx, dl[1] = ly;
      }
      double ov = measure;
      for (int d = 0; d < D; ++d)
        ov *= std::max(0.0, std::min(0.5 * ns.spacing[j], dl[d] + 0.5 * hq) -
                                std::max(-0.5 * ns.spacing[j], dl[d] - 0.5 * hq));
      if (ov > 0) {
        ns.volume[j] = std::max(0.0, ns.volume[j] - ov);
        changed[j] = 1;
      }
    });
  }
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (changed[i] || i >= n0) ns.sync_current(i);

  // The new nodes' values come from extrapolations and the masses moved between nodes: restore
  // the linear momentum exactly by a uniform velocity shift of the new nodes.
  if (!created.empty()) {
    const std::array<double, 3> P = linear_momentum(ns);
    double M = 0;
    for (std::uint32_t q : created) M += ns.density[q] * ns.volume[q];
    if (M > 0)
      for (std::uint32_t q : created)
        for (int d = 0; d < D; ++d) ns.v[d][q] += (st.momentum_before[d] - P[d]) / M;
  }
  st.parents = parents.size();
  st.children = created.size();
  if (inherit_boundary) inherit_loads_and_motions(m, n0, is_parent, true);
  finish_refinement(m, spec, memory, n0, std::move(changed), t0, st);
  return st;
}

}  // namespace periadapt
