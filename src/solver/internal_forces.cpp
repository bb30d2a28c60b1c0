#include "solver/internal_forces.hpp"

#include <algorithm>
#include <bit>

#include "discretize/families.hpp"
#include "discretize/partial_volume.hpp"
#include "material/contact.hpp"
#include "material/force_model.hpp"
#include "material/impactor.hpp"
#include "parallel/ghost_layer.hpp"
#include "parallel/held_rows.hpp"
#include "parallel/mpi_env.hpp"
#include "parallel/row_partition.hpp"
#include "solver/ghost_correction.hpp"

namespace periadapt {

namespace {

std::vector<double>* stretch_measure(Model& m) {
  return m.track_breakable_stretch ? &m.breakable_stretch : nullptr;
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
  if (m.partition.ghost_mode && m.partition.region_generation != m.partition.generation) {
    // The rows whose neighbours' positions the pass reads besides its own rows' neighbours.
    std::vector<std::uint32_t> around = m.partition.owned;
    auto add = [&](bool transpose) {
      const std::vector<std::uint32_t>& r = rows_around(m.partition, m.bonds, transpose);
      around.insert(around.end(), r.begin(), r.end());
    };
    if (dual) add(true);
    if (m.formulation.state_based()) add(false);
    refresh_ghost_layer(m.partition, m.bonds, around);
  }
  const std::vector<std::uint32_t> mine = owned_rows(m.partition, rows);
  // Energy densities when any rank asks (rank 0's observers ask where the others write nothing):
  // every owner must compute its rows' share.
  std::vector<double> w_scratch;
  const bool any_w = mpi::max(W != nullptr) > 0;  // collective: every rank calls it
  if (any_w && !W) W = &w_scratch;
  // The overlay counts its checks per rank: every rank keeps the totals.
  const std::uint64_t checks_before = m.pdro.enabled ? m.pdro.counters->checks.load() : 0;
  const std::uint64_t breaks_before = m.pdro.enabled ? m.pdro.counters->breaks.load() : 0;

  // Bonds broken by this rank's rows, for the exchange; or, where the formulation gathers the
  // breaks inside the pass, every rank's breaks, already applied everywhere.
  std::vector<std::uint64_t> broken_here, shared_already;
  const bool gathered = dual && m.formulation.gathers_breaks_in_pass();
  ForcePass pass;
  pass.allow_breaking = allow_breaking;
  pass.broken_log = gathered ? &shared_already : &broken_here;
  pass.W = W;
  pass.breakable_stretch = stretch_measure(m);
  DualRows split;
  std::vector<std::uint32_t> held_hits;  // rows with a gathered break (whose weights owners share)
  if (dual) {
    split.first = &rows_around(m.partition, m.bonds, true);
    split.rows = &m.partition.owned;
    split.own = m.partition.mine.data();
    // Breaks travel by name (row and place), which ranks holding other rows read alike.
    if (gathered) split.gather_breaks = [&](BrokenMemberships& b) {
      const BondFamilies& bf = m.bonds;
      std::vector<std::uint64_t> names;
      for (const auto& [k, o] : b) names.push_back(bf.name(o, k));
      const std::vector<std::uint64_t> all_names = mpi::all_gather(names);
      b.clear();
      for (std::uint64_t name : all_names) {
        const auto o = static_cast<std::uint32_t>(name >> 32);
        std::uint64_t k = kBondNotHeld;
        if (!bf.named(name, k)) k = kBondNotHeld;
        b.emplace_back(k, o);
        held_hits.push_back(o);
      }
      std::sort(b.begin(), b.end());
    };
    pass.split = &split;
  } else {
    pass.rows = &mine;
    if (m.formulation.state_based()) pass.dilatation_rows = &rows_around(m.partition, m.bonds, false);
  }

  // History laws: the bond states this rank's rows changed, (bond, new state), for the others.
  BondFamilies& bf = m.bonds;
  const bool history = m.formulation.keeps_bond_history();
  std::vector<double> before;
  if (history)
    for (std::uint32_t i : mine)
      before.insert(before.end(), bf.state.begin() + bf.begin(i), bf.state.begin() + bf.end(i));
  const std::size_t broken_in_pass = material_forces(m.nodes, bf, material_context(m), pass);
  if (gathered && m.partition.rows_held) {
    // A gathered break in a row this rank does not hold left that row's weight to its owner.
    std::sort(held_hits.begin(), held_hits.end());
    held_hits.erase(std::unique(held_hits.begin(), held_hits.end()), held_hits.end());
    share_owned_values(m.partition, m.nodes.broken_weight, &held_hits);
  }
  std::vector<std::uint64_t> changed_bonds;
  std::vector<double> changed_states;
  if (history) {
    std::size_t at = 0;
    for (std::uint32_t i : mine)
      for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k, ++at)
        if (std::bit_cast<std::uint64_t>(bf.state[k]) != std::bit_cast<std::uint64_t>(before[at])) {
          changed_bonds.push_back(bf.name(i, k));
          changed_states.push_back(bf.state[k]);
        }
  }
  if (gathered && log) log->insert(log->end(), shared_already.begin(), shared_already.end());
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
  const std::size_t broken = (gathered ? broken_in_pass : 0) +
                             share_force_pass(m.partition, m.nodes, m.bonds,
                                              rows ? mine : m.partition.owned, broken_here, log, W,
                                              stretch_measure(m));
  if (history) {
    const std::vector<std::uint64_t> all_bonds = mpi::all_gather(changed_bonds);
    const std::vector<double> all_states = mpi::all_gather(changed_states);
    for (std::size_t q = 0; q < all_bonds.size(); ++q) {
      std::uint64_t k = 0;
      if (m.bonds.named(all_bonds[q], k)) m.bonds.state[k] = all_states[q];
    }
  }
  // With the partition made, a run that asked for it keeps only the rows its passes read from
  // here on: its own and those its formulation reaches (held_reach).
  RowPartition& part = m.partition;
  if (part.hold_rows && !part.rows_held)
    rehold_rows(part, m.nodes, m.bonds, m.quadrature,
                held_reach(m.formulation.state_based(), m.formulation.dual_horizon));
  // Every rank holds the whole state: each adds the impactors' contact to the shared forces
  // and sums the impactors' reactions over all nodes in the serial run's order.
  if (!m.impactors.empty()) add_impactor_forces(m.impactors, m.nodes, rows, W);
  return broken;
}

// A serial pass over every row or the given ones (state-based: with their neighbours'
// dilatations).
std::size_t serial_forces(Model& m, bool allow_breaking, const std::vector<std::uint32_t>* rows,
                          std::vector<std::uint64_t>* log, std::vector<double>* W) {
  ForcePass pass;
  pass.allow_breaking = allow_breaking;
  pass.broken_log = log;
  pass.W = W;
  pass.rows = rows;
  std::vector<std::uint32_t> dilatation_rows;
  if (rows && m.formulation.state_based()) {
    const BondFamilies& bf = m.bonds;
    std::vector<char> in(m.nodes.size(), 0);
    for (std::uint32_t i : *rows) {
      in[i] = 1;
      if (i < bf.num_nodes())
        for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) in[bf.neighbor[k]] = 1;
    }
    for (std::size_t i = 0; i < in.size(); ++i)
      if (in[i]) dilatation_rows.push_back(static_cast<std::uint32_t>(i));
    pass.dilatation_rows = &dilatation_rows;
  }
  pass.breakable_stretch = stretch_measure(m);
  const std::size_t broken = material_forces(m.nodes, m.bonds, material_context(m), pass);
  if (m.contact.enabled) add_contact_forces(m.contact, m.nodes, rows, W);
  if (!m.impactors.empty()) add_impactor_forces(m.impactors, m.nodes, rows, W);
  return broken;
}

}  // namespace

std::size_t internal_forces(Model& m, bool allow_breaking, std::vector<std::uint64_t>* log,
                            std::vector<double>* W) {
  const std::size_t b = m.partition.active ? distributed_forces(m, allow_breaking, nullptr, log, W)
                                           : serial_forces(m, allow_breaking, nullptr, log, W);
  apply_ghost_correction(m, nullptr);
  return b;
}

std::size_t internal_forces_rows(Model& m, bool allow_breaking, const std::vector<std::uint32_t>& rows,
                                 std::vector<std::uint64_t>* log, std::vector<double>* W) {
  const std::size_t b = m.partition.active ? distributed_forces(m, allow_breaking, &rows, log, W)
                                           : serial_forces(m, allow_breaking, &rows, log, W);
  apply_ghost_correction(m, &rows);
  return b;
}

std::vector<std::uint32_t> rows_reading(const Model& m, const std::vector<std::uint32_t>& rows) {
  if (!m.formulation.state_based() || rows.empty()) return rows;
  const NodeSet& ns = m.nodes;
  const int D = ns.dim;
  // A row's members lie within its search radius, which grows with horizon and cell size.
  double hmax = 0, dxmax = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.flags[i] & kActive) {
      hmax = std::max(hmax, ns.horizon[i]);
      dxmax = std::max(dxmax, ns.spacing[i]);
    }
  return nodes_within(ns, rows, quadrature_search_radius(m.quadrature.rule, D, hmax, dxmax) * (1 + 1e-9));
}

void energy_density(const Model& m, std::vector<double>& W) {
  const RowPartition& p = m.partition;
  if (p.rows_held) {
    // Each owner's rows, to every rank (collective; runs with held rows have no contact or
    // impactors).
    W.assign(m.nodes.size(), 0.0);
    material_energy_density(m.nodes, m.bonds, material_context(m), W, &p.owned);
    share_owned_values(p, W);
    return;
  }
  material_energy_density(m.nodes, m.bonds, material_context(m), W);
  if (m.contact.enabled) add_contact_energy(m.contact, m.nodes, W);
  if (!m.impactors.empty()) add_impactor_energy(m.impactors, m.nodes, W);
}

void energy_density_rows(const Model& m, std::vector<double>& W,
                         const std::vector<std::uint32_t>& rows, bool own_rows_only) {
  const RowPartition& p = m.partition;
  own_rows_only = own_rows_only && p.active;
  if (!p.rows_held && !own_rows_only) {
    material_energy_density(m.nodes, m.bonds, material_context(m), W, &rows);
    return;
  }
  const std::vector<std::uint32_t> mine = owned_rows(p, &rows);
  material_energy_density(m.nodes, m.bonds, material_context(m), W, &mine);
  if (!own_rows_only) share_owned_values(p, W, &rows);
}

// Contact forces are not in the stress: they act between nodes that the bonds do not join.
void stress_density(const Model& m, std::vector<double>& sigma) {
  material_stress(m.nodes, m.bonds, material_context(m), sigma);
}

}  // namespace periadapt
