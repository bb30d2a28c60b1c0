// Checkpoint of the integrator between two steps: clock, work and counters, the multi-rate
// classes and cycles, the prescribed motions' reactions and the energies kept for the triggers.
// The undo copy is not kept: a step saves it afresh before it runs.
#include "core/binary_archive.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt {

void VelocityVerlet::save_state(ArchiveWriter& w) const {
  w.tag("VVRL");
  w.put(dt_);
  w.put(time_);
  w.put(step_);
  w.put(external_work_);
  w.put(last_power_);
  w.put(std::uint64_t{broken_total_});
  w.put(bond_evals_);
  w.put(runaway_limit_);
  w.put(undo_enabled_);
  w.put(multirate_);
  w.put(multirate_safety_);
  w.put(max_ratio_);
  w.put(energy_check_every_);
  w.put(rate_);
  w.put(target_);
  w.put(pending_);
  w.put(class_rows_);
  w.put(class_bonds_);
  w.put(pass_bonds_);
  w.put(pass_rows_);
  w.put(idle_rows_);
  w.put(full_pass_);
  w.put(synced_);
  w.put(syncing_);
  w.put(open_kick_);
  w.put(close_kick_);
  w.put(energy_requests_);
  w.put(energy_);
  // Densities of this rank's rows only belong to no state a restart could read them for.
  w.put(energy_owned_only_ ? -1L : energy_step_);
  w.put(fixed_dofs_);
  w.put(reaction_);
  w.put(body_);
  w.put(v_prev_fixed_);
  w.put(m_.impactors);
}

void VelocityVerlet::restore_state(ArchiveReader& r) {
  r.tag("VVRL");
  double dt = 0;
  r.get(dt);
  if (dt != dt_)
    throw ArchiveError("the checkpoint's time step " + std::to_string(dt) +
                       " s differs from this run's " + std::to_string(dt_) + " s");
  r.get(time_);
  r.get(step_);
  r.get(external_work_);
  r.get(last_power_);
  broken_total_ = r.get<std::uint64_t>();
  r.get(bond_evals_);
  r.get(runaway_limit_);
  r.get(undo_enabled_);
  r.get(multirate_);
  r.get(multirate_safety_);
  r.get(max_ratio_);
  r.get(energy_check_every_);
  r.get(rate_);
  if (m_.partition.active) m_.partition.rates = rate_;
  r.get(target_);
  r.get(pending_);
  r.get(class_rows_);
  r.get(class_bonds_);
  r.get(pass_bonds_);
  r.get(pass_rows_);
  r.get(idle_rows_);
  r.get(full_pass_);
  r.get(synced_);
  r.get(syncing_);
  r.get(open_kick_);
  r.get(close_kick_);
  r.get(energy_requests_);
  r.get(energy_);
  r.get(energy_step_);
  r.get(fixed_dofs_);
  r.get(reaction_);
  r.get(body_);
  for (auto& b : body_) b.clear();  // apply_loads() writes them afresh before any step reads them
  body_nodes_.clear();
  r.get(v_prev_fixed_);
  std::vector<Impactor> impactors;
  r.get(impactors);
  if (impactors.size() != m_.impactors.size())
    throw ArchiveError("the checkpoint and the deck differ in their impactors");
  m_.impactors = impactors;
  saved_ = Saved{};
}

}  // namespace periadapt
