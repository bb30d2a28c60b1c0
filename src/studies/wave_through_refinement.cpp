#include "studies/wave_through_refinement.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "analysis/energy.hpp"
#include "run/simulation.hpp"
#include "input/deck.hpp"
#include "setup/build_model.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt {

DeckBuilder gaussian_wave_deck(double spacing, double length, double width, double width_of_pulse,
                               double end_time) {
  DeckBuilder d;
  d.set("model.dimension", 2)
      .set("model.plane", "stress")
      .set("material.youngs_modulus", 1.0)
      .set("material.density", 1.0)
      .set("discretization.spacing", spacing)
      .set("discretization.horizon_factor", 3.0)
      .set("discretization.registration", "node_on_edge")
      .set("discretization.quadrature", "pa_pdlammps")
      .set("discretization.body.box.min", {0.0, 0.0})
      .set("discretization.body.box.max", {length, width})
      .set("initial_conditions.displacement",
           std::vector<std::string>{fmt::format("2e-4*exp(-(x/{})^2)", width_of_pulse), "0"})
      .set("damage.enabled", false)
      // One step for every run (the level-3 delta grid's stable step is 1.16e-4), so the probe
      // histories of refined and uniform runs line up sample by sample.
      .set("solver.time_step", 1.0e-4)
      .set("solver.end_time", end_time);
  return d;
}

WaveRun run_wave(const Deck& dk, std::array<double, 2> probe) {
  Model m = build_model(dk);
  const TimeStepChoice ts = choose_time_step(dk, m);
  VelocityVerlet vv(m, ts.dt);
  vv.initialize();
  const NodeSet& ns = m.nodes;
  std::size_t p = 0;
  double best = INFINITY;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    const double d = std::hypot(ns.x[0][i] - probe[0], ns.x[1][i] - probe[1]);
    if (d < best) best = d, p = i;
  }
  WaveRun r;
  std::vector<double> W;
  r.e0 = kinetic_energy(ns) + strain_energy(m, W);
  std::vector<double> wpk(ns.size(), 0.0), kpk(ns.size(), 0.0), epk(ns.size(), 0.0);
  auto track = [&]() {
    for (std::size_t i = 0; i < ns.size(); ++i) {
      double v2 = 0;
      for (std::size_t d = 0; d < 2; ++d) v2 += ns.v[d][i] * ns.v[d][i];
      const double k = 0.5 * ns.density[i] * v2;
      wpk[i] = std::max(wpk[i], W[i]);
      kpk[i] = std::max(kpk[i], k);
      epk[i] = std::max(epk[i], W[i] + k);
    }
  };
  track();
  for (long s = 1; s <= ts.steps; ++s) {
    vv.step();
    r.t.push_back(vv.time());
    r.probe.push_back(ns.u[0][p]);
    strain_energy(m, W);
    track();
  }
  r.e_end = kinetic_energy(ns) + strain_energy(m, W);
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    ++r.nodes;
    r.pos.push_back({ns.x[0][i], ns.x[1][i]});
    r.w_peak.push_back(wpk[i]);
    r.k_peak.push_back(kpk[i]);
    r.e_peak.push_back(epk[i]);
  }
  return r;
}

std::array<double, 2> peak_drops(const WaveRun& refined, const WaveRun& uniform, double dx, long nx,
                                 const std::function<bool(double, double)>& inside,
                                 std::vector<double> WaveRun::*which) {
  auto index = [&](double x, double y) { return std::lround(y / dx) * nx + std::lround(x / dx); };
  std::vector<double> grid(uniform.pos.size(), 0.0);
  for (std::size_t k = 0; k < uniform.pos.size(); ++k) {
    const long c = index(uniform.pos[k][0], uniform.pos[k][1]);
    if (c >= 0 && static_cast<std::size_t>(c) < grid.size()) grid[static_cast<std::size_t>(c)] = (uniform.*which)[k];
  }
  double hi = -INFINITY, lo = INFINITY;
  for (std::size_t k = 0; k < refined.pos.size(); ++k) {
    if (!inside(refined.pos[k][0], refined.pos[k][1])) continue;
    const long c = index(refined.pos[k][0], refined.pos[k][1]);
    if (c < 0 || static_cast<std::size_t>(c) >= grid.size() || !(grid[static_cast<std::size_t>(c)] > 0)) continue;
    const double ref = grid[static_cast<std::size_t>(c)];
    const double drop = 100.0 * (ref - (refined.*which)[k]) / ref;
    hi = std::max(hi, drop);
    lo = std::min(lo, drop);
  }
  return {hi, lo};
}

double reflection_percent(const WaveRun& refined, const WaveRun& uniform) {
  double amp = 0, du = 0;
  for (double u : uniform.probe) amp = std::max(amp, std::abs(u));
  for (std::size_t k = 0; k < refined.probe.size() && k < uniform.probe.size(); ++k)
    du = std::max(du, std::abs(refined.probe[k] - uniform.probe[k]));
  return amp > 0 ? 100 * du / amp : 0.0;
}

}  // namespace periadapt
