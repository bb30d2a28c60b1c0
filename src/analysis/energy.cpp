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

MomentumAndKinetic momentum_and_kinetic(const NodeSet& ns) {
  constexpr std::size_t kBlock = 4096;
  const std::size_t n = ns.size(), nb = (n + kBlock - 1) / kBlock;
  std::vector<std::array<double, 5>> part(nb, {0, 0, 0, 0, 0});
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < nb; ++b) {
    std::array<double, 5> s{0, 0, 0, 0, 0};
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      if (!(ns.flags[i] & kActive)) continue;
      const double mass = ns.density[i] * ns.volume[i];
      double v2 = 0;
      for (int d = 0; d < ns.dim; ++d) {
        s[static_cast<std::size_t>(d)] += mass * ns.v[d][i];
        v2 += ns.v[d][i] * ns.v[d][i];
      }
      s[3] += 0.5 * mass * v2;
      s[4] += mass * std::sqrt(v2);
    }
    part[b] = s;
  }
  MomentumAndKinetic r;
  for (const auto& s : part) {
    for (int d = 0; d < 3; ++d) r.momentum[static_cast<std::size_t>(d)] += s[static_cast<std::size_t>(d)];
    r.kinetic += s[3];
    r.momentum_scale += s[4];
  }
  return r;
}

std::array<double, 3> linear_momentum(const NodeSet& ns) { return momentum_and_kinetic(ns).momentum; }

}  // namespace periadapt
