#pragma once
// output.regions: sums over named parts of the body, for history.csv and summary.json. Per
// region, over its active nodes (membership re-read from the shape, so children created by
// refinement count): the net internal force (sum f V, the bond forces the rest of the body exerts
// across the region's boundary; bonds inside it cancel), the volume-weighted mean displacement,
// the strain energy sum W V and the kinetic energy.
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "input/deck.hpp"
#include "model/model.hpp"

namespace periadapt {

using ForceField = std::array<std::vector<double>, 3>;

// "region_NAME_fx_N,...,region_NAME_ux_m,...,region_NAME_strain_energy_J,
// region_NAME_kinetic_energy_J," with a trailing comma (empty without regions).
std::string region_header(const std::vector<NamedRegion>& regions, int dim);

// The values under region_header. `W`: strain-energy density per node; `f`: internal force
// density per component (ns.f, or the static solve's K u). Exact sums: with an active partition
// `p` each rank adds its own nodes (collective; analysis/energy.hpp), the serial run's bits.
std::string region_columns(const std::vector<NamedRegion>& regions, const NodeSet& ns,
                           const std::vector<double>& W, const ForceField& f,
                           const RowPartition* p = nullptr);

// {NAME: {internal_force_N, mean_displacement_m, strain_energy_J, kinetic_energy_J}}.
nlohmann::json regions_json(const std::vector<NamedRegion>& regions, const NodeSet& ns,
                            const std::vector<double>& W, const ForceField& f,
                            const RowPartition* p = nullptr);

}  // namespace periadapt
