#include "run/output_regions.hpp"

#include <fmt/format.h>

#include <array>

#include "core/exact_sum.hpp"
#include "io/csv_column.hpp"
#include "parallel/owned_sums.hpp"

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

// Per region: force (3), u V (3), V, W V, kinetic energy.
constexpr std::size_t kSums = 9;

std::vector<RegionSums> sums(const std::vector<NamedRegion>& regions, const NodeSet& ns,
                             const std::vector<double>& W, const ForceField& f,
                             const RowPartition* p) {
  std::vector<ExactSum> acc(regions.size() * kSums);
  const CountedNodes counted = counted_nodes(p, ns.size());
  for (std::size_t r = 0; r < regions.size(); ++r) {
    ExactSum* a = &acc[r * kSums];
    for (std::size_t i = 0; i < ns.size(); ++i) {
      if (!counted(i) || !holds(regions[r].region, ns, i)) continue;
      const double V = ns.volume[i];
      double v2 = 0;
      for (int d = 0; d < ns.dim; ++d) {
        a[d].add(f[d][i] * V);
        a[3 + d].add(ns.u[d][i] * V);
        v2 += ns.v[d][i] * ns.v[d][i];
      }
      a[6].add(V);
      if (i < W.size()) a[7].add(W[i] * V);
      a[8].add(0.5 * ns.density[i] * V * v2);
    }
  }
  add_over_ranks(p, acc.data(), acc.size());
  std::vector<RegionSums> out(regions.size());
  for (std::size_t r = 0; r < regions.size(); ++r) {
    const ExactSum* a = &acc[r * kSums];
    const double volume = a[6].value();
    for (int d = 0; d < 3; ++d) {
      out[r].force[d] = a[d].value();
      out[r].displacement[d] = volume > 0 ? a[3 + d].value() / volume : 0.0;
    }
    out[r].strain_energy = a[7].value();
    out[r].kinetic_energy = a[8].value();
  }
  return out;
}

std::string column_base(const std::string& name) { return csv_column_stem("region_", name); }

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
                           const std::vector<double>& W, const ForceField& f,
                           const RowPartition* p) {
  std::string c;
  for (const RegionSums& s : sums(regions, ns, W, f, p)) {
    for (int d = 0; d < ns.dim; ++d) c += fmt::format("{:.9e},", s.force[d]);
    for (int d = 0; d < ns.dim; ++d) c += fmt::format("{:.9e},", s.displacement[d]);
    c += fmt::format("{:.9e},{:.9e},", s.strain_energy, s.kinetic_energy);
  }
  return c;
}

nlohmann::json regions_json(const std::vector<NamedRegion>& regions, const NodeSet& ns,
                            const std::vector<double>& W, const ForceField& f,
                            const RowPartition* p) {
  nlohmann::json j = nlohmann::json::object();
  const std::vector<RegionSums> all = sums(regions, ns, W, f, p);
  for (std::size_t k = 0; k < regions.size(); ++k) {
    const NamedRegion& r = regions[k];
    const RegionSums& s = all[k];
    j[r.name] = {{"internal_force_N", std::vector<double>(s.force.begin(), s.force.begin() + ns.dim)},
                 {"mean_displacement_m",
                  std::vector<double>(s.displacement.begin(), s.displacement.begin() + ns.dim)},
                 {"strain_energy_J", s.strain_energy},
                 {"kinetic_energy_J", s.kinetic_energy}};
  }
  return j;
}

}  // namespace periadapt
