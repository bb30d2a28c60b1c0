#include "run/refinement_forecast.hpp"

#include <cmath>
#include <vector>

#include "adapt/triggers.hpp"
#include "run/simulation.hpp"
#include "setup/build_model.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt {

RefinementForecast forecast_refinement(const Deck& dk, double max_bond_evaluations) {
  RefinementForecast fc;
  const AdaptSpec& spec = dk.adapt;
  if (!spec.enabled || !spec.stretch_fraction || dk.solver != Deck::SolverType::Explicit) return fc;
  // The coarse grid: the profile's set-up zones (which `check` reports as initial zones) left out.
  Deck coarse = dk;
  coarse.adapt.refine_crack_tips = coarse.adapt.refine_motions = false;
  Model m = build_model(coarse);
  m.damage_enabled = false;
  const TimeStepChoice ts = choose_time_step(dk, m);
  // The coarse grid's own stable step: nothing is refined here.
  const double dt = dk.safety * ts.dt_crit;
  const long steps = static_cast<long>(std::ceil(dk.end_time / dt));
  fc.bond_evaluations = static_cast<double>(m.bonds.num_bonds()) * static_cast<double>(steps);
  if (fc.bond_evaluations > max_bond_evaluations) return fc;
  fc.ran = true;
  const std::vector<char> refinable = refinable_nodes(m, spec);
  std::vector<char> refined(m.nodes.size(), 0);
  VelocityVerlet vv(m, dt);
  vv.initialize();
  for (long s = 1; s <= steps; ++s) {
    if (!vv.step()) break;
    if (s % spec.check_every != 0 && s != steps) continue;
    std::vector<std::uint32_t> parents = apply_visibility(
        m, stretch_trigger(m, spec, *spec.stretch_fraction, refinable), refinable,
        spec.visibility_factor);
    if (spec.refine_loads) add_loaded_neighbours(m, refinable, parents);
    for (std::uint32_t p : parents) refined[p] = 1;
    fc.time = vv.time();
    if (!stretch_trigger(m, spec, 1.0, refinable).empty()) {
      fc.initiates = true;
      break;
    }
  }
  const NodeSet& ns = m.nodes;
  double vol = 0, vol_refined = 0;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    vol += ns.volume[i];
    fc.refinable += refinable[i] != 0;
    if (!refined[i]) continue;
    ++fc.parents;
    vol_refined += ns.volume[i];
  }
  fc.volume_fraction = vol > 0 ? vol_refined / vol : 0.0;
  return fc;
}

}  // namespace periadapt
