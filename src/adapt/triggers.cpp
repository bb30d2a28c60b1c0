#include "adapt/triggers.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/breakable_stretch.hpp"
#include "core/cell_grid.hpp"
#include "adapt/refine.hpp"
#include "discretize/families.hpp"

namespace periadapt {

std::vector<char> refinable_nodes(const Model& m, const AdaptSpec& spec) {
  const NodeSet& ns = m.nodes;
  std::vector<char> r(ns.size(), 0);
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive) || (ns.flags[i] & kBoundary) || ns.level[i] >= spec.max_level)
      continue;
    if (spec.region &&
        !spec.region->contains({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, 1e-9 * ns.spacing[i]))
      continue;
    r[i] = 1;
  }
  if (!spec.refine_loads)
    for (const BodyLoad& l : m.loads)
      for (std::uint32_t i : l.nodes) r[i] = 0;
  return r;
}

void add_loaded_neighbours(const Model& m, const std::vector<char>& refinable,
                           std::vector<std::uint32_t>& parents, const std::vector<char>* only) {
  if (parents.empty() || m.loads.empty()) return;
  const NodeSet& ns = m.nodes;
  std::vector<char> mark(ns.size(), 0);
  for (std::uint32_t p : parents) mark[p] = 1;
  const std::size_t before = parents.size();
  for (const BodyLoad& l : m.loads)
    for (std::uint32_t i : l.nodes) {
      if (mark[i] || !refinable[i] || (only && !(*only)[i])) continue;
      for (std::uint64_t k = m.bonds.begin(i); k < m.bonds.end(i); ++k) {
        const std::uint32_t j = m.bonds.neighbor[k];
        if (mark[j] == 1 && ns.level[j] >= ns.level[i]) {
          mark[i] = 2;
          parents.push_back(i);
          break;
        }
      }
    }
  if (parents.size() > before) std::sort(parents.begin(), parents.end());
}

std::vector<std::uint32_t> energy_trigger(const Model& m, const std::vector<double>& W,
                                          double alpha, const std::vector<char>& refinable) {
  const NodeSet& ns = m.nodes;
  // W_max over the nodes that can still be refined or are already refined: nodes that never
  // refine (loaded, prescribed motion) can carry boundary-layer energies (an impact, a clamp)
  // that would otherwise switch the trigger off for the whole body.
  double wmax = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if ((ns.flags[i] & kActive) && !(ns.flags[i] & kBoundary)) wmax = std::max(wmax, W[i]);
  std::vector<std::uint32_t> out;
  if (!(wmax > 0)) return out;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if ((refinable[i] || ((ns.flags[i] & kActive) && ns.level[i] > 0)) && W[i] >= alpha * wmax)
      out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

std::vector<std::uint32_t> stretch_trigger(const Model& m, const AdaptSpec& spec, double beta,
                                           const std::vector<char>& refinable,
                                           const std::vector<std::uint32_t>* rows) {
  const NodeSet& ns = m.nodes;
  const std::size_t n = ns.size();
  std::vector<char> hot(n, 0);
  // The force passes measured it already (row-local PMB): their latest value per row.
  const bool tracked = m.track_breakable_stretch && m.breakable_stretch.size() == n;
  const std::size_t count = rows ? rows->size() : n;
#pragma omp parallel for schedule(guided, 64)
  for (std::size_t r = 0; r < count; ++r) {
    const std::size_t i = rows ? (*rows)[r] : r;
    if (!refinable[i]) continue;
    // s0 ~ delta^(-1/2) for every law and scaling (thesis Eqs. 2.15, 2.21): the critical stretch
    // of this node's children.
    // A history law is refined before its bonds leave the elastic branch: children start with
    // fresh histories.
    const double limit =
        beta * std::min(m.material.onset_stretch,
                        ns.critical_stretch[i] *
                            std::sqrt(failure_horizon(m, spec, i) / level_horizon(m, spec, ns.level[i] + 1)));
    // The force pass's value counts every breakable bond and so bounds the own-level measure
    // from above: only rows it passes are swept again.
    hot[i] = (!tracked || m.breakable_stretch[i] >= limit) &&
             largest_breakable_stretch_own_level(m, static_cast<std::uint32_t>(i)) >= limit;
  }
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < n; ++i)
    if (hot[i]) out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

std::vector<std::uint32_t> near_cracks(const Model& m, const std::vector<std::uint32_t>& ids,
                                       double reach) {
  const NodeSet& ns = m.nodes;
  if (ids.empty()) return {};
  double hmax = 0;
  for (std::uint32_t i : ids) hmax = std::max(hmax, ns.horizon[i]);
  std::vector<std::uint32_t> cracked = active_nodes_near(ns, ids, reach * hmax * (1 + 1e-9));
  std::erase_if(cracked, [&](std::uint32_t j) { return !(ns.broken_weight[j] > 0); });
  if (cracked.empty()) return {};
  CellGrid grid(ns.dim, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()}, cracked, reach * hmax);
  std::vector<std::uint32_t> out;
  for (std::uint32_t i : ids) {
    bool near = false;
    grid.for_each_within({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, reach * ns.horizon[i] * (1 + 1e-12),
                         [&](std::uint32_t, double) { near = true; });
    if (near) out.push_back(i);
  }
  return out;
}

std::vector<std::uint32_t> damage_trigger(const Model& m, const std::vector<std::uint32_t>& damaged,
                                          const std::vector<char>& refinable) {
  const NodeSet& ns = m.nodes;
  std::vector<std::uint32_t> out;
  for (std::uint32_t i : damaged)
    if (i < ns.size() && (refinable[i] || ((ns.flags[i] & kActive) && ns.level[i] > 0)))
      out.push_back(i);
  return out;
}

std::vector<std::uint32_t> apply_visibility(const Model& m, const std::vector<std::uint32_t>& ids,
                                            const std::vector<char>& refinable,
                                            double radius_factor) {
  const NodeSet& ns = m.nodes;
  std::vector<char> mark(ns.size(), 0);
  if (ids.empty()) return {};
  double dmax = 0;  // the largest horizon a candidate can have
  for (std::size_t j = 0; j < ns.size(); ++j)
    if (refinable[j]) dmax = std::max(dmax, ns.horizon[j]);
  if (!(dmax > 0)) return {};
  for (std::uint32_t i : ids) mark[i] = refinable[i];
  // Only refinable nodes within reach of an identified one can be marked: the cell list holds
  // those alone (the box around the identified nodes, widened by the largest reach).
  double hmax = dmax;
  for (std::uint32_t i : ids) hmax = std::max(hmax, ns.horizon[i]);
  std::vector<std::uint32_t> candidates = active_nodes_near(ns, ids, radius_factor * hmax * (1 + 1e-9));
  std::erase_if(candidates, [&](std::uint32_t j) { return !refinable[j]; });
  CellGrid grid(ns.dim, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()}, candidates,
                radius_factor * dmax);
  for (std::uint32_t i : ids) {
    const double reach = radius_factor * std::max(ns.horizon[i], dmax) * (1 + 1e-12);
    grid.for_each_within({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, reach, [&](std::uint32_t j, double d2) {
      const double r = radius_factor * std::max(ns.horizon[i], ns.horizon[j]) * (1 + 1e-12);
      if (ns.level[j] <= ns.level[i] && d2 <= r * r) mark[j] = 1;
    });
  }
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (mark[i]) out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

}  // namespace periadapt
