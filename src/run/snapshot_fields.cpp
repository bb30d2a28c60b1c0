#include "run/snapshot_fields.hpp"

namespace periadapt {

std::vector<PointField> snapshot_fields(const Model& m, const std::vector<double>& W) {
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
  return f;
}

}  // namespace periadapt
