#include "run/snapshot_fields.hpp"

#include "analysis/breakable_stretch.hpp"
#include "core/visible_gradient.hpp"
#include "solver/internal_forces.hpp"

namespace periadapt {

std::vector<PointField> snapshot_fields(const Model& m, const std::vector<double>& W,
                                        bool stress) {
  const NodeSet& ns = m.nodes;
  const std::size_t n = ns.size();
  std::vector<PointField> f;
  auto vec3 = [&](const std::string& name, const std::array<std::vector<double>, 3>& a) {
    PointField p{name, 3, std::vector<double>(n * 3, 0.0)};
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < ns.dim; ++d) p.data[i * 3 + d] = a[d][i];
    f.push_back(std::move(p));
  };
  vec3("displacement", ns.u);
  vec3("velocity", ns.v);
  PointField dmg{"damage", 1, std::vector<double>(n)};
  for (std::size_t i = 0; i < n; ++i) dmg.data[i] = ns.damage(i);
  f.push_back(std::move(dmg));
  f.push_back({"energy_density", 1, W});
  f.push_back({"horizon", 1, ns.horizon});
  PointField lvl{"refinement_level", 1, std::vector<double>(n)};
  for (std::size_t i = 0; i < n; ++i) lvl.data[i] = ns.level[i];
  f.push_back(std::move(lvl));
  f.push_back({"volume", 1, ns.volume});
  f.push_back({"stretch_ratio", 1, breakable_stretch_ratio(m)});
  if (!ns.block.empty()) {
    PointField blk{"block", 1, std::vector<double>(n)};
    for (std::size_t i = 0; i < n; ++i) blk.data[i] = ns.block[i];
    f.push_back(std::move(blk));
  }
  if (!stress) return f;
  PointField sig{"stress", 9, {}};
  stress_density(m, sig.data);
  f.push_back(std::move(sig));
  PointField eps{"strain", 9, std::vector<double>(9 * n, 0.0)};
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    double G[3][3];
    fit_gradient(ns, m.bonds, static_cast<std::uint32_t>(i), ns.u, G);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) eps.data[9 * i + 3 * a + b] = 0.5 * (G[a][b] + G[b][a]);
  }
  f.push_back(std::move(eps));
  if (m.formulation.state_based()) f.push_back({"dilatation", 1, m.lps_scratch.theta});
  return f;
}

}  // namespace periadapt
