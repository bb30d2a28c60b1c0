#include "run/output_regions.hpp"

#include <fmt/format.h>

#include <array>
#include <cctype>

namespace periadapt {

namespace {

struct RegionSums {
  Vec3 force{0, 0, 0}, displacement{0, 0, 0};
  double strain_energy = 0, kinetic_energy = 0;
};

bool holds(const Shape& region, const NodeSet& ns, std::size_t i) {
  const double tol = 1e-9 * ns.spacing[i];
  return (ns.flags[i] & kActive) && region.contains({ns.x[0][i], ns.x[1][i], ns.x[2][i]}, tol);
}

RegionSums sums(const Shape& region, const NodeSet& ns, const std::vector<double>& W,
                const ForceField& f) {
  RegionSums r;
  double volume = 0;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!holds(region, ns, i)) continue;
    const double V = ns.volume[i];
    double v2 = 0;
    for (int d = 0; d < ns.dim; ++d) {
      r.force[d] += f[d][i] * V;
      r.displacement[d] += ns.u[d][i] * V;
      v2 += ns.v[d][i] * ns.v[d][i];
    }
    volume += V;
    if (i < W.size()) r.strain_energy += W[i] * V;
    r.kinetic_energy += 0.5 * ns.density[i] * V * v2;
  }
  for (double& c : r.displacement) c = volume > 0 ? c / volume : 0.0;
  return r;
}

std::string column_base(const std::string& name) {
  std::string s = "region_";
  for (char c : name) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return s;
}

}  // namespace

std::string region_header(const std::vector<NamedRegion>& regions, int dim) {
  std::string h;
  const char* axes = "xyz";
  for (const NamedRegion& r : regions) {
    const std::string b = column_base(r.name);
    for (int d = 0; d < dim; ++d) h += fmt::format("{}_f{}_N,", b, axes[d]);
    for (int d = 0; d < dim; ++d) h += fmt::format("{}_u{}_m,", b, axes[d]);
    h += b + "_strain_energy_J," + b + "_kinetic_energy_J,";
  }
  return h;
}

std::string region_columns(const std::vector<NamedRegion>& regions, const NodeSet& ns,
                           const std::vector<double>& W, const ForceField& f) {
  std::string c;
  for (const NamedRegion& r : regions) {
    const RegionSums s = sums(r.region, ns, W, f);
    for (int d = 0; d < ns.dim; ++d) c += fmt::format("{:.9e},", s.force[d]);
    for (int d = 0; d < ns.dim; ++d) c += fmt::format("{:.9e},", s.displacement[d]);
    c += fmt::format("{:.9e},{:.9e},", s.strain_energy, s.kinetic_energy);
  }
  return c;
}

nlohmann::json regions_json(const std::vector<NamedRegion>& regions, const NodeSet& ns,
                            const std::vector<double>& W, const ForceField& f) {
  nlohmann::json j = nlohmann::json::object();
  for (const NamedRegion& r : regions) {
    const RegionSums s = sums(r.region, ns, W, f);
    j[r.name] = {{"internal_force_N", std::vector<double>(s.force.begin(), s.force.begin() + ns.dim)},
                 {"mean_displacement_m",
                  std::vector<double>(s.displacement.begin(), s.displacement.begin() + ns.dim)},
                 {"strain_energy_J", s.strain_energy},
                 {"kinetic_energy_J", s.kinetic_energy}};
  }
  return j;
}

}  // namespace periadapt
