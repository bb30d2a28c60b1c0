#include "adapt/coarsen.hpp"

#include <chrono>

#include "adapt/crack_memory.hpp"
#include "analysis/energy.hpp"

namespace periadapt {

namespace {

// Children of every parent, from the parent links (ids ascending).
std::vector<std::vector<std::uint32_t>> children_of(const NodeSet& ns) {
  std::vector<std::vector<std::uint32_t>> ch(ns.size());
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.parent[i] >= 0) ch[static_cast<std::size_t>(ns.parent[i])].push_back(static_cast<std::uint32_t>(i));
  return ch;
}

// A broken bond of node i that no pre-crack explains (pre-crack cuts are redone on any grid).
bool has_dynamic_break(const Model& m, std::size_t i) {
  const NodeSet& ns = m.nodes;
  for (std::uint64_t k = m.bonds.begin(i); k < m.bonds.end(i); ++k) {
    if (BondFamilies::intact(m.bonds.beta[k])) continue;
    const std::uint32_t j = m.bonds.neighbor[k];
    const Vec3 p{ns.x[0][i], ns.x[1][i], ns.x[2][i]}, q{ns.x[0][j], ns.x[1][j], ns.x[2][j]};
    bool pre = false;
    for (const PreCrack& c : m.cracks)
      pre = pre || (c.planar3d ? bond_crosses_quad(p, q, c.points)
                               : bond_crosses_segment(p, q, c.points[0], c.points[1]));
    if (!pre) return true;
  }
  return false;
}


}  // namespace

std::vector<std::uint32_t> coarsenable_parents(const Model& m) {
  const NodeSet& ns = m.nodes;
  const auto ch = children_of(ns);
  std::vector<std::uint32_t> out;
  for (std::size_t p = 0; p < ns.size(); ++p) {
    if (ch[p].empty() || (ns.flags[p] & kActive)) continue;
    bool ok = true;
    for (std::uint32_t c : ch[p]) {
      // Active leaf (no children of its own), no prescribed motion, nothing broken by dynamics.
      if (!(ns.flags[c] & kActive) || !ch[c].empty() || (ns.flags[c] & kBoundary)) ok = false;
      else if (ns.broken_weight[c] > 0 && has_dynamic_break(m, c)) ok = false;  // cracks stay fine
      if (!ok) break;
    }
    if (ok) out.push_back(static_cast<std::uint32_t>(p));
  }
  return out;
}

RefineStats coarsen_nodes(Model& m, const std::vector<std::uint32_t>& parents) {
  const auto t0 = std::chrono::steady_clock::now();
  RefineStats st;
  NodeSet& ns = m.nodes;
  if (parents.empty()) return st;
  const MomentumAndKinetic before = momentum_and_kinetic(ns, m.partition.active ? &m.partition : nullptr);
  st.momentum_before = before.momentum;
  st.kinetic_before = before.kinetic;
  st.momentum_scale = before.momentum_scale;
  const auto ch = children_of(ns);
  std::vector<char> vanishing(ns.size(), 0);
  for (std::uint32_t p : parents)
    for (std::uint32_t c : ch[p]) vanishing[c] = 1;
  const CrackMemory memory = remember_cracks(m, vanishing);
  for (std::uint32_t p : parents) {
    double mass = 0, mu[3] = {0, 0, 0}, mv[3] = {0, 0, 0}, ma[3] = {0, 0, 0};
    for (std::uint32_t c : ch[p]) {
      const double w = ns.density[c] * ns.volume[c];
      mass += w;
      for (int d = 0; d < ns.dim; ++d)
        mu[d] += w * ns.u[d][c], mv[d] += w * ns.v[d][c], ma[d] += w * ns.a[d][c];
    }
    for (int d = 0; d < ns.dim; ++d) {
      ns.u[d][p] = mu[d] / mass;
      ns.v[d][p] = mv[d] / mass;
      ns.a[d][p] = ma[d] / mass;
    }
    for (std::uint32_t c : ch[p]) {
      // Retired for good: the slot stays (ids are stable) but no longer counts as a child, so a
      // later refinement of p starts a fresh generation.
      ns.parent[c] = -1;
      ns.flags[c] = static_cast<std::uint8_t>(ns.flags[c] & ~kActive);
      for (int d = 0; d < 3; ++d) ns.v[d][c] = ns.a[d][c] = ns.f[d][c] = 0.0;
    }
    ns.flags[p] |= kActive;
    ns.sync_current(p);
    ++st.parents;
    st.children += ch[p].size();
  }
  // Every id already exists: "old" pairs keep their state, the revived parents' bonds are new.
  std::vector<char> changed(vanishing);
  for (std::uint32_t p : parents) changed[p] = 1;
  st.rebuilt = rebuild_families(m, memory, ns.size(), changed);
  const MomentumAndKinetic after = momentum_and_kinetic(ns, m.partition.active ? &m.partition : nullptr);
  st.momentum_after = after.momentum;
  st.kinetic_after = after.kinetic;
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return st;
}

}  // namespace periadapt
