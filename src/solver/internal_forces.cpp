#include "solver/internal_forces.hpp"

#include <algorithm>
#include <bit>

#include "material/contact.hpp"
#include "material/impactor.hpp"
#include "material/lps_dual.hpp"
#include "material/pmb.hpp"
#include "material/pmb_dual.hpp"
#include "parallel/mpi_env.hpp"
#include "parallel/row_partition.hpp"

namespace periadapt {

namespace {

using Kind = Formulation::Kind;

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

// Row-local forms (plain PMB, history laws): all rows or the given ones.
std::size_t row_local_forces(Model& m, bool allow_breaking, std::vector<std::uint64_t>* log,
                             std::vector<double>* W, const std::vector<std::uint32_t>* rows) {
  std::vector<double>* stretch = m.track_breakable_stretch ? &m.breakable_stretch : nullptr;
  if (m.formulation.kind == Kind::HistoryLaw) {
    BondLawCall c = law_call(m, allow_breaking, log, W, rows);
    c.breakable_stretch = stretch;
    return m.formulation.law->forces(m.nodes, m.bonds, c);
  }
  return pmb_forces(m.nodes, m.bonds, m.material.shape, allow_breaking, log, W, &m.pdro,
                    m.material.thermal_strain, rows, stretch, &m.block_pairs)
      .newly_broken;
}

std::size_t material_forces(Model& m, bool allow_breaking, std::vector<std::uint64_t>* log,
                            std::vector<double>* W) {
  const Formulation& f = m.formulation;
  if (f.kind == Kind::Lps)
    return f.dual_horizon
               ? lps_dual_forces(m.nodes, m.bonds, m.material.shape, m.material.lps_constants,
                                 allow_breaking, m.lps_scratch, log, W)
               : lps_forces(m.nodes, m.bonds, m.material.shape, m.material.lps_constants,
                            allow_breaking, m.lps_scratch, log, W, &m.pdro);
  if (f.dual_horizon && f.kind == Kind::HistoryLaw)
    return f.law->dual_forces(m.nodes, m.bonds, law_call(m, allow_breaking, log, W));
  if (f.dual_horizon)
    return pmb_dual_forces(m.nodes, m.bonds, m.material.shape, allow_breaking, log, W);
  return row_local_forces(m, allow_breaking, log, W, nullptr);
}

// A distributed run's pass (parallel/row_partition.hpp): this rank's share of `rows` (all rows
// when null), then the owners share their results (forces, broken bonds, and the bond states a
// history law changed). The dual-horizon pairing evaluates the memberships of its rows and of
// the rows whose memberships point at them, and gathers its rows' forces (material/dual_rows.hpp).
std::size_t distributed_forces(Model& m, bool allow_breaking, const std::vector<std::uint32_t>* rows,
                               std::vector<std::uint64_t>* log, std::vector<double>* W) {
  const bool dual = m.formulation.dual_horizon;
  // The dual pairing's forces gather memberships from other rows: a full pass only.
  if (dual) rows = nullptr;
  refresh_partition(m.partition, m.nodes, m.bonds);
  const std::vector<std::uint32_t> mine = owned_rows(m.partition, rows);
  std::vector<std::uint64_t> broken_here;
  // Energy densities when any rank asks (rank 0's observers ask where the others write nothing):
  // every owner must compute its rows' share.
  std::vector<double> w_scratch;
  const bool any_w = mpi::max(W != nullptr) > 0;  // collective: every rank calls it
  if (any_w && !W) W = &w_scratch;
  std::vector<double>* stretch = m.track_breakable_stretch ? &m.breakable_stretch : nullptr;
  // History laws: the bond states this rank's rows changed, (bond, new state), for the others.
  std::vector<std::uint64_t> changed_bonds;
  std::vector<double> changed_states;
  // The overlay counts its checks per rank: every rank keeps the totals.
  const std::uint64_t checks_before = m.pdro.enabled ? m.pdro.counters->checks.load() : 0;
  const std::uint64_t breaks_before = m.pdro.enabled ? m.pdro.counters->breaks.load() : 0;
  DualRows split;
  std::vector<std::uint64_t> shared_already;  // LPS dual: every rank's breaks, applied in the pass
  if (dual) {
    split.first = &rows_around(m.partition, m.bonds, true);
    split.rows = &m.partition.owned;
    split.own = m.partition.mine.data();
  }
  if (m.formulation.kind == Kind::HistoryLaw) {
    BondFamilies& bf = m.bonds;
    std::vector<double> before;
    for (std::uint32_t i : mine) before.insert(before.end(), bf.state.begin() + bf.begin(i),
                                               bf.state.begin() + bf.end(i));
    BondLawCall c = law_call(m, allow_breaking, &broken_here, W, dual ? nullptr : &mine);
    c.breakable_stretch = stretch;
    if (dual) {
      c.split = &split;
      m.formulation.law->dual_forces(m.nodes, bf, c);
    } else {
      m.formulation.law->forces(m.nodes, bf, c);
    }
    std::size_t at = 0;
    for (std::uint32_t i : mine)
      for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k, ++at)
        if (std::bit_cast<std::uint64_t>(bf.state[k]) != std::bit_cast<std::uint64_t>(before[at])) {
          changed_bonds.push_back(k);
          changed_states.push_back(bf.state[k]);
        }
  } else if (m.formulation.kind == Kind::Lps && dual) {
    // The dilatations read every bond: all ranks' breaks are applied before them, here.
    split.gather_breaks = [](BrokenMemberships& b) {
      std::vector<std::uint64_t> bonds;
      std::vector<std::uint32_t> owners;
      for (const auto& [k, o] : b) {
        bonds.push_back(k);
        owners.push_back(o);
      }
      const std::vector<std::uint64_t> all_bonds = mpi::all_gather(bonds);
      const std::vector<std::uint32_t> all_owners = mpi::all_gather(owners);
      b.clear();
      for (std::size_t q = 0; q < all_bonds.size(); ++q) b.emplace_back(all_bonds[q], all_owners[q]);
      std::sort(b.begin(), b.end());
    };
    lps_dual_forces(m.nodes, m.bonds, m.material.shape, m.material.lps_constants, allow_breaking,
                    m.lps_scratch, &shared_already, W, split);
    if (log) log->insert(log->end(), shared_already.begin(), shared_already.end());
  } else if (dual) {
    pmb_dual_forces(m.nodes, m.bonds, m.material.shape, allow_breaking, &broken_here, W, split);
  } else if (m.formulation.kind == Kind::Lps)
    lps_forces(m.nodes, m.bonds, m.material.shape, m.material.lps_constants, allow_breaking,
               m.lps_scratch, &broken_here, W, &m.pdro, &mine,
               &rows_around(m.partition, m.bonds, false));
  else
    pmb_forces(m.nodes, m.bonds, m.material.shape, allow_breaking, &broken_here, W, &m.pdro,
               m.material.thermal_strain, &mine, stretch, &m.block_pairs);
  if (m.contact.enabled) add_contact_forces(m.contact, m.nodes, &mine, W);
  if (m.pdro.enabled) {
    const std::vector<std::uint64_t> counts = mpi::all_gather(std::vector<std::uint64_t>{
        m.pdro.counters->checks.load() - checks_before, m.pdro.counters->breaks.load() - breaks_before});
    std::uint64_t checks = checks_before, breaks = breaks_before;
    for (std::size_t r = 0; r + 1 < counts.size(); r += 2) {
      checks += counts[r];
      breaks += counts[r + 1];
    }
    m.pdro.counters->checks = checks;
    m.pdro.counters->breaks = breaks;
  }
  const std::size_t broken = shared_already.size() +
                             share_force_pass(m.partition, m.nodes, m.bonds,
                                              rows ? mine : m.partition.owned, broken_here, log, W,
                                              stretch);
  if (m.formulation.kind == Kind::HistoryLaw) {
    const std::vector<std::uint64_t> all_bonds = mpi::all_gather(changed_bonds);
    const std::vector<double> all_states = mpi::all_gather(changed_states);
    for (std::size_t q = 0; q < all_bonds.size(); ++q) m.bonds.state[all_bonds[q]] = all_states[q];
  }
  // Every rank holds the whole state: each adds the impactors' contact to the shared forces
  // and sums the impactors' reactions over all nodes in the serial run's order.
  if (!m.impactors.empty()) add_impactor_forces(m.impactors, m.nodes, rows, W);
  return broken;
}

}  // namespace

std::size_t internal_forces(Model& m, bool allow_breaking, std::vector<std::uint64_t>* log,
                            std::vector<double>* W) {
  if (m.partition.active) return distributed_forces(m, allow_breaking, nullptr, log, W);
  const std::size_t broken = material_forces(m, allow_breaking, log, W);
  if (m.contact.enabled) add_contact_forces(m.contact, m.nodes, nullptr, W);
  if (!m.impactors.empty()) add_impactor_forces(m.impactors, m.nodes, nullptr, W);
  return broken;
}

std::size_t internal_forces_rows(Model& m, bool allow_breaking, const std::vector<std::uint32_t>& rows,
                                 std::vector<std::uint64_t>* log, std::vector<double>* W) {
  if (m.partition.active) return distributed_forces(m, allow_breaking, &rows, log, W);
  const std::size_t broken = row_local_forces(m, allow_breaking, log, W, &rows);
  if (m.contact.enabled) add_contact_forces(m.contact, m.nodes, &rows, W);
  if (!m.impactors.empty()) add_impactor_forces(m.impactors, m.nodes, &rows, W);
  return broken;
}

namespace {
void material_energy_density(const Model& m, std::vector<double>& W) {
  switch (m.formulation.kind) {
    case Kind::HistoryLaw:
      m.formulation.law->energy_density(m.nodes, m.bonds, law_call(m), W);
      return;
    case Kind::Lps:
      lps_energy_density(m.nodes, m.bonds, m.material.shape, m.material.lps_constants,
                         m.lps_scratch, W, !m.formulation.dual_horizon);
      return;
    case Kind::Pmb:
      pmb_energy_density(m.nodes, m.bonds, m.material.shape, W, m.material.thermal_strain,
                         nullptr, &m.block_pairs);
      return;
  }
}

}  // namespace

void energy_density(const Model& m, std::vector<double>& W) {
  material_energy_density(m, W);
  if (m.contact.enabled) add_contact_energy(m.contact, m.nodes, W);
  if (!m.impactors.empty()) add_impactor_energy(m.impactors, m.nodes, W);
}

// Contact forces are not in the stress: they act between nodes that the bonds do not join.
void stress_density(const Model& m, std::vector<double>& sigma) {
  switch (m.formulation.kind) {
    case Kind::HistoryLaw:
      m.formulation.law->stress(m.nodes, m.bonds, law_call(m), sigma);
      return;
    case Kind::Lps:
      lps_stress(m.nodes, m.bonds, m.material.shape, m.material.lps_constants, m.lps_scratch,
                 sigma, !m.formulation.dual_horizon);
      return;
    case Kind::Pmb:
      pmb_stress(m.nodes, m.bonds, m.material.shape, sigma, m.material.thermal_strain,
                 &m.block_pairs);
      return;
  }
}

}  // namespace periadapt
