#include "analysis/energy.hpp"

#include "solver/internal_forces.hpp"

namespace periadapt {

double kinetic_energy(const NodeSet& ns) {
  double e = 0;
  const std::size_t n = ns.size();
#pragma omp parallel for reduction(+ : e) schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    double v2 = 0;
    for (int d = 0; d < ns.dim; ++d) v2 += ns.v[d][i] * ns.v[d][i];
    e += 0.5 * ns.density[i] * ns.volume[i] * v2;
  }
  return e;
}

double strain_energy(const Model& model, std::vector<double>& W) {
  energy_density(model, W);
  double e = 0;
  const std::size_t n = W.size();
#pragma omp parallel for reduction(+ : e) schedule(static)
  for (std::size_t i = 0; i < n; ++i) e += W[i] * model.nodes.volume[i];
  return e;
}

std::array<double, 3> linear_momentum(const NodeSet& ns) {
  std::array<double, 3> p{0, 0, 0};
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    for (int d = 0; d < ns.dim; ++d) p[d] += ns.density[i] * ns.volume[i] * ns.v[d][i];
  }
  return p;
}

}  // namespace periadapt
