#include "analysis/energy.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/exact_sum.hpp"
#include "parallel/owned_sums.hpp"
#include "solver/internal_forces.hpp"

namespace periadapt {

namespace {

// The exact sum of term(i) over the nodes i < n this rank counts, over the ranks under `p`.
template <class Term>
double node_sum(const RowPartition* p, std::size_t n, std::size_t slots, const Term& term) {
  const CountedNodes counted = counted_nodes(p, slots);
  ExactSum total;
#pragma omp parallel
  {
    ExactSum mine;
#pragma omp for schedule(static) nowait
    for (std::size_t i = 0; i < n; ++i)
      if (counted(i)) mine.add(term(i));
#pragma omp critical(periadapt_node_sum)
    total.add(mine);
  }
  add_over_ranks(p, &total, 1);
  return total.value();
}

}  // namespace

double kinetic_energy(const NodeSet& ns, const RowPartition* p) {
  return node_sum(p, ns.size(), ns.size(), [&](std::size_t i) {
    if (!(ns.flags[i] & kActive)) return 0.0;
    double v2 = 0;
    for (int d = 0; d < ns.dim; ++d) v2 += ns.v[d][i] * ns.v[d][i];
    return 0.5 * ns.density[i] * ns.volume[i] * v2;
  });
}

double strain_energy_of(const NodeSet& nodes, const std::vector<double>& W, const RowPartition* p) {
  return node_sum(p, W.size(), nodes.size(), [&](std::size_t i) { return W[i] * nodes.volume[i]; });
}

double strain_energy(const Model& model, std::vector<double>& W) {
  energy_density(model, W);
  return strain_energy_of(model.nodes, W);
}

MomentumAndKinetic momentum_and_kinetic(const NodeSet& ns, const RowPartition* p) {
  const CountedNodes counted = counted_nodes(p, ns.size());
  const std::size_t n = ns.size();
  std::array<ExactSum, 5> total;  // momentum (3), kinetic energy, sum of m |v|
#pragma omp parallel
  {
    std::array<ExactSum, 5> mine;
#pragma omp for schedule(static) nowait
    for (std::size_t i = 0; i < n; ++i) {
      if (!(ns.flags[i] & kActive) || !counted(i)) continue;
      const double mass = ns.density[i] * ns.volume[i];
      double v2 = 0;
      for (int d = 0; d < ns.dim; ++d) {
        mine[static_cast<std::size_t>(d)].add(mass * ns.v[d][i]);
        v2 += ns.v[d][i] * ns.v[d][i];
      }
      mine[3].add(0.5 * mass * v2);
      mine[4].add(mass * std::sqrt(v2));
    }
#pragma omp critical(periadapt_momentum_sum)
    for (std::size_t k = 0; k < total.size(); ++k) total[k].add(mine[k]);
  }
  add_over_ranks(p, total.data(), total.size());
  MomentumAndKinetic r;
  for (std::size_t d = 0; d < 3; ++d) r.momentum[d] = total[d].value();
  r.kinetic = total[3].value();
  r.momentum_scale = total[4].value();
  return r;
}

std::array<double, 3> linear_momentum(const NodeSet& ns) { return momentum_and_kinetic(ns).momentum; }

}  // namespace periadapt
