#include "solver/internal_forces.hpp"

#include "material/pmb.hpp"
#include "material/lps_dual.hpp"
#include "material/pmb_dual.hpp"

namespace periadapt {

namespace {

BondLawCall law_call(const Model& m, bool allow_breaking = false,
                     std::vector<std::uint64_t>* log = nullptr, std::vector<double>* W = nullptr,
                     const std::vector<std::uint32_t>* rows = nullptr) {
  BondLawCall c;
  c.shape = m.material.shape;
  c.onset_stretch = m.material.onset_stretch;
  c.allow_breaking = allow_breaking;
  c.broken_log = log;
  c.W = W;
  c.rows = rows;
  return c;
}

std::size_t law_forces(Model& m, bool allow_breaking, std::vector<std::uint64_t>* log,
                       std::vector<double>* W, const std::vector<std::uint32_t>* rows) {
  BondLawCall c = law_call(m, allow_breaking, log, W, rows);
  c.breakable_stretch = m.track_breakable_stretch ? &m.breakable_stretch : nullptr;
  return m.material.bond_law->forces(m.nodes, m.bonds, c);
}

}  // namespace

std::size_t internal_forces(Model& m, bool allow_breaking, std::vector<std::uint64_t>* log,
                            std::vector<double>* W) {
  if (m.material.bond_law)
    return law_forces(m, allow_breaking, log, W, nullptr);
  if (m.material.lps && m.dual_horizon)
    return lps_dual_forces(m.nodes, m.bonds, m.material.shape, m.material.lps_constants,
                           allow_breaking, m.lps_scratch, log, W);
  if (m.material.lps)
    return lps_forces(m.nodes, m.bonds, m.material.shape, m.material.lps_constants, allow_breaking,
                      m.lps_scratch, log, W, &m.pdro);
  if (m.dual_horizon)
    return pmb_dual_forces(m.nodes, m.bonds, m.material.shape, allow_breaking, log, W);
  return pmb_forces(m.nodes, m.bonds, m.material.shape, allow_breaking, log, W, &m.pdro,
                    m.material.thermal_strain, nullptr,
                    m.track_breakable_stretch ? &m.breakable_stretch : nullptr)
      .newly_broken;
}

bool forces_are_row_local(const Model& m) { return !m.material.lps && !m.dual_horizon; }

std::size_t internal_forces_rows(Model& m, bool allow_breaking, const std::vector<std::uint32_t>& rows,
                                 std::vector<std::uint64_t>* log, std::vector<double>* W) {
  if (m.material.bond_law)
    return law_forces(m, allow_breaking, log, W, &rows);
  return pmb_forces(m.nodes, m.bonds, m.material.shape, allow_breaking, log, W, &m.pdro,
                    m.material.thermal_strain, &rows,
                    m.track_breakable_stretch ? &m.breakable_stretch : nullptr)
      .newly_broken;
}

void energy_density(const Model& m, std::vector<double>& W) {
  if (m.material.bond_law)
    m.material.bond_law->energy_density(m.nodes, m.bonds, law_call(m), W);
  else if (m.material.lps)
    lps_energy_density(m.nodes, m.bonds, m.material.shape, m.material.lps_constants,
                       m.lps_scratch, W, !m.dual_horizon);
  else
    pmb_energy_density(m.nodes, m.bonds, m.material.shape, W, m.material.thermal_strain);
}

void stress_density(const Model& m, std::vector<double>& sigma) {
  if (m.material.bond_law)
    m.material.bond_law->stress(m.nodes, m.bonds, law_call(m), sigma);
  else if (m.material.lps)
    lps_stress(m.nodes, m.bonds, m.material.shape, m.material.lps_constants, m.lps_scratch, sigma,
               !m.dual_horizon);
  else
    pmb_stress(m.nodes, m.bonds, m.material.shape, sigma, m.material.thermal_strain);
}

}  // namespace periadapt
