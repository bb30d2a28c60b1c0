#include "solver/stable_time_step.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "material/contact.hpp"
#include "material/impactor.hpp"

namespace periadapt {

StableStep stable_time_step(const Model& model) {
  std::vector<double> K;
  material_stiffness_sum(model.nodes, model.bonds, material_context(model), K);
  if (model.contact.enabled)
    for (std::size_t i = 0; i < K.size(); ++i)
      if (model.nodes.flags[i] & kActive) K[i] += contact_stiffness_bound(model.contact, model.nodes, i);
  if (!model.impactors.empty())
    for (std::size_t i = 0; i < K.size(); ++i)
      if (model.nodes.flags[i] & kActive) K[i] += impactor_stiffness_bound(model.impactors, model.nodes, i);
  StableStep best{std::numeric_limits<double>::infinity(), 0};
  for (std::size_t i = 0; i < K.size(); ++i) {
    if (!(model.nodes.flags[i] & kActive) || K[i] <= 0) continue;
    const double dt = std::sqrt(2.0 * model.nodes.density[i] / K[i]);
    if (dt < best.dt) best = {dt, i};
  }
  return best;
}

StableStep stable_time_step(const Model& model, const std::vector<std::uint32_t>& nodes) {
  const NodeSet& ns = model.nodes;
  const BondFamilies& bf = model.bonds;
  const MaterialContext ctx = material_context(model);
  StableStep best{std::numeric_limits<double>::infinity(), 0};
  for (std::uint32_t i : nodes) {
    if (!(ns.flags[i] & kActive)) continue;
    const double k = material_stiffness_row(ns, bf, ctx, i) +
                     (model.contact.enabled ? contact_stiffness_bound(model.contact, ns, i) : 0.0) +
                     impactor_stiffness_bound(model.impactors, ns, i);
    if (!(k > 0)) continue;
    const double dt = std::sqrt(2.0 * ns.density[i] / k);
    if (dt < best.dt) best = {dt, i};
  }
  return best;
}

}  // namespace periadapt
