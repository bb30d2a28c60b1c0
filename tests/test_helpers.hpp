#pragma once
// Small builders shared by the tests: deck pieces, and models on uniform grids.
#include <algorithm>
#include <initializer_list>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "adapt/refine.hpp"
#include "analysis/energy.hpp"
#include "run/simulation.hpp"
#include "input/deck.hpp"
#include "input/deck_builder.hpp"
#include "setup/build_model.hpp"
#include "solver/internal_forces.hpp"
#include "solver/velocity_verlet.hpp"

namespace periadapt::test {

// The active 2D nodes of `level` within r (per axis) of (cx, cy): parents for refine_nodes.
inline std::vector<std::uint32_t> active_near(const NodeSet& ns, double cx, double cy, double r,
                                              int level) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t i = 0; i < ns.size(); ++i)
    if ((ns.flags[i] & kActive) && ns.level[i] == level && std::abs(ns.x[0][i] - cx) < r &&
        std::abs(ns.x[1][i] - cy) < r)
      out.push_back(i);
  return out;
}

// Refinement events one after another, each of the active 2D nodes of `level` within r of
// (cx, cy), up to max_level 2: zones of two levels side by side.
struct Zone {
  double cx, cy, r;
  int level;
};
inline void refine_zones(Model& m, std::initializer_list<Zone> zones) {
  AdaptSpec spec;
  spec.enabled = true;
  spec.max_level = 2;
  for (const Zone& z : zones) refine_nodes(m, active_near(m.nodes, z.cx, z.cy, z.r, z.level), spec);
}

// A box region, {box: {min: lo, max: hi}} (loads, boundary conditions, holes, no_fail zones,
// refinement zones).
inline DeckBuilder box(const std::vector<double>& lo, const std::vector<double>& hi) {
  return DeckBuilder().set("box.min", lo).set("box.max", hi);
}

// The components of a prescribed motion or an initial field, each an expression in x, y, z, t;
// std::nullopt leaves a component free (YAML null).
using Components = std::vector<std::optional<std::string>>;

// A 2D plane-stress soda-lime glass plate (E = 72 GPa, rho = 2440 kg/m^3, G0 = 135 J/m^2) on a
// 1 mm grid with m = 3, over the box [lo, hi]: the tests' common specimen.
inline DeckBuilder glass_plate(std::initializer_list<double> lo, std::initializer_list<double> hi) {
  DeckBuilder d;
  d.set("model.dimension", 2)
      .set("model.plane", "stress")
      .set("material.youngs_modulus", 72.0e9)
      .set("material.density", 2440.0)
      .set("material.fracture_energy", 135.0)
      .set("discretization.spacing", 0.001)
      .set("discretization.horizon_factor", 3.0)
      .set("discretization.body.box.min", lo)
      .set("discretization.body.box.max", hi);
  return d;
}

// Displaces every node by the homogeneous strain eps (u = eps x, first `ns.dim` components).
inline void apply_homogeneous_strain(NodeSet& ns, const double eps[3][3]) {
  for (std::size_t i = 0; i < ns.size(); ++i) {
    for (int d = 0; d < ns.dim; ++d) {
      double u = 0;
      for (int e = 0; e < ns.dim; ++e) u += eps[d][e] * ns.x[e][i];
      ns.u[d][i] = u;
    }
    ns.sync_current(i);
  }
}

// A 1D bar (nodes on x in [0, length]) stretched homogeneously by s: forces from one pass (bonds
// break where the law says), and the tension carried across its middle (the net internal force
// the left half exerts on the right half, negated).
inline double bar_tension(Model& m, double s, double length) {
  NodeSet& ns = m.nodes;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    ns.u[0][i] = s * ns.x[0][i];
    ns.sync_current(i);
  }
  internal_forces(m, true);
  double right = 0;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.x[0][i] > 0.5 * length) right += ns.f[0][i] * ns.volume[i];
  return -right;
}

struct EnergyRun {
  bool ok = true;
  double e0 = 0, worst_drift = 0, max_kinetic = 0;  // drift relative to e0
};

// Runs a deck's explicit steps and follows kinetic + strain energy (every `every` steps).
inline EnergyRun run_energy_history(const Deck& dk, int every = 1) {
  Model m = build_model(dk);
  const TimeStepChoice ts = choose_time_step(dk, m);
  VelocityVerlet vv(m, ts.dt);
  vv.initialize();
  std::vector<double> W;
  EnergyRun r;
  r.e0 = kinetic_energy(m.nodes) + strain_energy(m, W);
  for (long s = 0; s < ts.steps; ++s) {
    if (!vv.step()) {
      r.ok = false;
      return r;
    }
    if (s % every) continue;
    const double K = kinetic_energy(m.nodes);
    r.max_kinetic = std::max(r.max_kinetic, K);
    r.worst_drift = std::max(r.worst_drift, std::abs(K + strain_energy(m, W) - r.e0) / r.e0);
  }
  return r;
}

// Linear-momentum change over `steps` explicit steps, relative to sum m |v| at the start.
inline double momentum_drift(Model& m, double dt, int steps) {
  VelocityVerlet vv(m, dt);
  vv.initialize();
  const auto p0 = linear_momentum(m.nodes);
  double scale = 0;
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (m.nodes.flags[i] & kActive)
      for (int d = 0; d < m.nodes.dim; ++d)
        scale += m.nodes.density[i] * m.nodes.volume[i] * std::abs(m.nodes.v[d][i]);
  for (int s = 0; s < steps; ++s)
    if (!vv.step()) return INFINITY;
  const auto p1 = linear_momentum(m.nodes);
  return std::hypot(p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]) / scale;
}

}  // namespace periadapt::test
