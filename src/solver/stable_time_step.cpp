#include "solver/stable_time_step.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "material/contact.hpp"
#include "material/impactor.hpp"
#include "parallel/mpi_env.hpp"

namespace periadapt {

namespace {

// sum_j C_ij V_j per node, with the contact and impactor bounds.
std::vector<double> stiffness_sums(const Model& model) {
  std::vector<double> K;
  material_stiffness_sum(model.nodes, model.bonds, material_context(model), K);
  if (model.contact.enabled)
    for (std::size_t i = 0; i < K.size(); ++i)
      if (model.nodes.flags[i] & kActive) K[i] += contact_stiffness_bound(model.contact, model.nodes, i);
  if (!model.impactors.empty())
    for (std::size_t i = 0; i < K.size(); ++i)
      if (model.nodes.flags[i] & kActive) K[i] += impactor_stiffness_bound(model.impactors, model.nodes, i);
  return K;
}

StableStep smallest_step(const Model& model, const std::vector<double>* scale) {
  const std::vector<double> K = stiffness_sums(model);
  // Ranks holding their own bond rows (parallel/held_rows.hpp) bound their own rows; the
  // smallest over the ranks, the lowest node on a tie, is the serial run's.
  const RowPartition& p = model.partition;
  StableStep best{std::numeric_limits<double>::infinity(), 0};
  for (std::size_t i = 0; i < K.size(); ++i) {
    if (!(model.nodes.flags[i] & kActive) || K[i] <= 0 || (p.rows_held && !p.mine[i])) continue;
    const double dt = std::sqrt(2.0 * model.nodes.density[i] / K[i]) * (scale ? (*scale)[i] : 1.0);
    if (dt < best.dt) best = {dt, i};
  }
  if (!p.rows_held) return best;
  const std::vector<double> all =
      mpi::all_gather(std::vector<double>{best.dt, static_cast<double>(best.node)});
  for (std::size_t r = 0; r + 1 < all.size(); r += 2) {
    const auto node = static_cast<std::size_t>(all[r + 1]);
    if (all[r] < best.dt || (all[r] == best.dt && node < best.node)) best = {all[r], node};
  }
  return best;
}

}  // namespace

StableStep stable_time_step(const Model& model) { return smallest_step(model, nullptr); }

StableStep scaled_stable_time_step(const Model& model, const std::vector<double>& scale) {
  return smallest_step(model, &scale);
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
