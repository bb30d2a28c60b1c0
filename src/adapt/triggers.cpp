#include "adapt/triggers.hpp"

#include <algorithm>
#include <cmath>

#include "core/cell_grid.hpp"

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
  for (const BodyLoad& l : m.loads)
    for (std::uint32_t i : l.nodes) r[i] = 0;
  return r;
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
    if (refinable[i] && W[i] >= alpha * wmax) out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

std::vector<std::uint32_t> damage_trigger(const Model& m, const std::vector<double>& before,
                                          const std::vector<char>& refinable) {
  const NodeSet& ns = m.nodes;
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < before.size() && i < ns.size(); ++i)
    if (refinable[i] && ns.damage(i) > before[i]) out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

std::vector<std::uint32_t> apply_visibility(const Model& m, const std::vector<std::uint32_t>& ids,
                                            const std::vector<char>& refinable,
                                            double radius_factor) {
  const NodeSet& ns = m.nodes;
  std::vector<char> mark(ns.size(), 0);
  double hmax = 0;
  for (std::uint32_t i : ids) {
    mark[i] = 1;
    hmax = std::max(hmax, radius_factor * ns.horizon[i]);
  }
  if (ids.empty()) return {};
  CellGrid grid(ns.dim, {ns.x[0].data(), ns.x[1].data(), ns.x[2].data()}, ns.size(), hmax);
  for (std::uint32_t i : ids)
    grid.for_each_within({ns.x[0][i], ns.x[1][i], ns.x[2][i]},
                         radius_factor * ns.horizon[i] * (1 + 1e-12),
                         [&](std::uint32_t j, double) {
                           if (refinable[j] && ns.level[j] <= ns.level[i]) mark[j] = 1;
                         });
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (mark[i]) out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

}  // namespace periadapt
