#include "adapt/adaptor.hpp"

#include <fmt/core.h>

#include "adapt/triggers.hpp"
#include "solver/internal_forces.hpp"
#include "solver/stable_time_step.hpp"

namespace periadapt {

Adaptor::Adaptor(Model& m, VelocityVerlet& vv, const AdaptSpec& spec)
    : m_(m), vv_(vv), spec_(spec) {
  // The energy trigger reads W from the solver's own force pass instead of a second bond loop.
  if (spec_.energy_fraction) vv_.set_energy_output(&W_);
}

std::size_t Adaptor::nodes_added() const {
  std::size_t n = 0;
  for (const RefinementEvent& e : events_) n += e.stats.children;
  return n;
}

void Adaptor::refine(const std::vector<std::uint32_t>& ids, const char* trigger) {
  const std::vector<char> refinable = refinable_nodes(m_, spec_);
  const std::vector<std::uint32_t> parents = apply_visibility(m_, ids, refinable);
  if (parents.empty()) return;
  RefinementEvent ev;
  ev.step = vv_.step_count();
  ev.time = vv_.time();
  ev.trigger = trigger;
  ev.identified = ids.size();
  ev.stats = refine_nodes(m_, parents, spec_);
  std::size_t active = 0;
  for (auto f : m_.nodes.flags) active += (f & kActive) != 0;
  ev.active_nodes = active;
  ev.bonds = m_.bonds.num_bonds();
  const StableStep s = stable_time_step(m_);
  ev.dt_stable = s.dt;
  events_.push_back(ev);
  if (vv_.dt() > s.dt * (1 + 1e-9))
    throw UnstableAfterRefinement(fmt::format(
        "refinement at t = {:.4e} s made the time step unstable: dt = {:.4e} s exceeds the stable "
        "step {:.4e} s of the refined grid (node {}, level {}); lower solver.time_step",
        vv_.time(), vv_.dt(), s.dt, s.node, static_cast<int>(m_.nodes.level[s.node])));
  vv_.refresh();
}

bool Adaptor::step() {
  const bool live = spec_.enabled && vv_.time() + vv_.dt() >= spec_.start_time * (1 - 1e-12);
  if (!live) return vv_.step();
  const NodeSet& ns = m_.nodes;
  if (spec_.damage_trigger) {
    vv_.set_undo(true);
    // Each pass refines by at most one level, so max_level + 1 passes always suffice.
    for (int pass = 0;; ++pass) {
      damage_before_.resize(ns.size());
      for (std::size_t i = 0; i < ns.size(); ++i) damage_before_[i] = ns.damage(i);
      if (!vv_.step()) return false;
      const auto ids = damage_trigger(m_, damage_before_, refinable_nodes(m_, spec_));
      if (ids.empty() || pass > spec_.max_level) break;
      vv_.undo_last_step();
      const std::size_t before = ns.size();
      refine(ids, "damage");
      if (ns.size() == before) {  // nothing refinable after all: keep the step as computed
        if (!vv_.step()) return false;
        break;
      }
    }
  } else if (!vv_.step()) {
    return false;
  }
  if (spec_.energy_fraction && vv_.step_count() % spec_.check_every == 0) {
    if (W_.size() != ns.size()) energy_density(m_, W_);
    const auto ids = energy_trigger(m_, W_, *spec_.energy_fraction, refinable_nodes(m_, spec_));
    if (!ids.empty()) refine(ids, "energy");
  }
  return true;
}

}  // namespace periadapt
