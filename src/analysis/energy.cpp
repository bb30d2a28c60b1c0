#include "analysis/energy.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "solver/internal_forces.hpp"

namespace periadapt {

double kinetic_energy(const NodeSet& ns) { return momentum_and_kinetic(ns).kinetic; }

double strain_energy_of(const NodeSet& nodes, const std::vector<double>& W) {
  double e = 0;
  const std::size_t n = W.size();
#pragma omp parallel for reduction(+ : e) schedule(static)
  for (std::size_t i = 0; i < n; ++i) e += W[i] * nodes.volume[i];
  return e;
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
