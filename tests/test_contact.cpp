// Short-range contact (material/contact.hpp): two equal bars meeting end to end exchange their
// velocities (elementary rod impact theory: after the contact time 2 L / c the striker stands and
// the struck bar moves off at the striker's speed), with momentum conserved to round-off and the
// energy (kinetic + bond + contact) kept by the symplectic step.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "analysis/energy.hpp"
#include "input/deck_builder.hpp"
#include "setup/build_model.hpp"
#include "run/simulation.hpp"
#include "solver/internal_forces.hpp"
#include "solver/velocity_verlet.hpp"

using namespace periadapt;

namespace {

constexpr double kL = 50.0;   // bar length (dx = 1, horizon 3)
constexpr double kV = 0.01;   // striker speed (wave speed 1: strain 1e-2 at most)

// E = rho = 1 (wave speed 1), dx = 1, m = 3, no damage.
DeckBuilder unit_grid(int dim) {
  DeckBuilder d;
  d.set("model.dimension", dim)
      .set("material.youngs_modulus", 1.0)
      .set("material.density", 1.0)
      .set("discretization.spacing", 1.0)
      .set("discretization.horizon_factor", 3.0)
      .set("damage.enabled", false);
  return d;
}

// Bars [0, 50] and [54, 104]: the 4-spacing gap is wider than the horizon (no bond across it)
// and (5 spacings between the end nodes) closes to the contact distance 1.35 dx after 3.65 / v.
DeckBuilder bars(int dim) {
  DeckBuilder d = unit_grid(dim);
  d.set("contact.enabled", true).set("solver.end_time", 3.65 / kV + 2.5 * kL);
  if (dim == 1) {
    d.set("discretization.body.box.min", {0.0})
        .set("discretization.body.box.max", {2 * kL + 4})
        .append("discretization.holes",
                DeckBuilder().set("box.min", {kL}).set("box.max", {kL + 4}))
        .set("initial_conditions.velocity", std::vector<std::string>{fmt::format("x < {} ? {} : 0", kL, kV)});
  }
  return d;
}

struct Motion {
  double p = 0, e = 0, v_left = 0, v_right = 0, k_right = 0;
};

Motion measure(const Model& m) {
  const NodeSet& ns = m.nodes;
  Motion r;
  double ml = 0, mr = 0;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    const double mass = ns.density[i] * ns.volume[i];
    r.p += mass * ns.v[0][i];
    (ns.x[0][i] < kL ? r.v_left : r.v_right) += mass * ns.v[0][i];
    (ns.x[0][i] < kL ? ml : mr) += mass;
    if (ns.x[0][i] > kL) r.k_right += 0.5 * mass * ns.v[0][i] * ns.v[0][i];
  }
  r.v_left /= ml;
  r.v_right /= mr;
  std::vector<double> W;
  r.e = kinetic_energy(ns) + strain_energy(m, W);
  return r;
}

}  // namespace

TEST(Contact, EqualBarsExchangeTheirVelocitiesWithMomentumConserved) {
  const Deck dk = bars(1).build("colliding bars");
  Model m = build_model(dk);
  const TimeStepChoice ts = choose_time_step(dk, m);
  VelocityVerlet vv(m, ts.dt);
  vv.initialize();
  const Motion start = measure(m);
  double worst_p = 0, worst_e = 0;
  for (long s = 1; s <= ts.steps; ++s) {
    ASSERT_TRUE(vv.step());
    const Motion now = measure(m);
    worst_p = std::max(worst_p, std::abs(now.p - start.p) / std::abs(start.p));
    worst_e = std::max(worst_e, std::abs(now.e - start.e) / start.e);
  }
  const Motion end = measure(m);
  std::printf("momentum %.3e, energy %.3e, v_left/v %.4f, v_right/v %.4f, K_right/K0 %.4f\n",
              worst_p, worst_e, end.v_left / kV, end.v_right / kV, end.k_right / start.e);
  // Equal and opposite pair forces: momentum to round-off.
  EXPECT_LT(worst_p, 1e-12);
  // Velocity Verlet's energy error, which falls with the step (0.40% at the default step, 0.044%
  // at half of it); the contact pair energy is part of the total.
  EXPECT_LT(worst_e, 0.01);
  // Rod impact theory: exact exchange. The discrete bar's dispersion leaves a trailing wave
  // behind the front (measured: 1.2% of v in the striker, 1.8% of the energy not in the struck
  // bar's motion); 5% bounds it.
  EXPECT_LT(std::abs(end.v_left), 0.05 * kV);
  EXPECT_NEAR(end.v_right, kV, 0.05 * kV);
  EXPECT_GT(end.k_right / start.e, 0.95);
}

// Contact acts only where nodes come closer than 0.9 of their reference distance (or 1.35
// spacings): a uniformly compressed grid feels nothing at 5% and is pushed apart at 12%.
TEST(Contact, ActsOnlyBelowTheContactDistance) {
  for (int dim : {2, 3}) {
    DeckBuilder d = unit_grid(dim);
    d.set("discretization.body.box.min", std::vector<double>(dim, 0.0))
        .set("discretization.body.box.max", std::vector<double>(dim, 12.0))
        .set("solver.steps", 1);
    Model plain = build_model(d.build("block"));
    Model touching = build_model(d.set("contact.enabled", true).build("block with contact"));
    for (double squeeze : {0.05, 0.12}) {
      for (Model* m : {&plain, &touching}) {
        NodeSet& ns = m->nodes;
        for (std::size_t i = 0; i < ns.size(); ++i)
          for (int k = 0; k < dim; ++k) {
            ns.u[k][i] = -squeeze * (ns.x[k][i] - 6.0);
            ns.cur[4 * i + k] = ns.x[k][i] + ns.u[k][i];
          }
        internal_forces(*m, false);
      }
      double diff = 0, scale = 0;
      for (std::size_t i = 0; i < plain.nodes.size(); ++i)
        for (int k = 0; k < dim; ++k) {
          diff = std::max(diff, std::abs(touching.nodes.f[k][i] - plain.nodes.f[k][i]));
          scale = std::max(scale, std::abs(plain.nodes.f[k][i]));
        }
      if (squeeze < 0.1)
        EXPECT_EQ(diff, 0.0) << dim << "D, squeeze " << squeeze;
      else
        EXPECT_GT(diff, 0.1 * scale) << dim << "D, squeeze " << squeeze;
    }
  }
}

// A rigid disk strikes a resting glass block: the body's and the impactor's momentum together
// are kept to round-off, and kinetic + strain + contact energy plus the impactor's kinetic energy
// is kept by the symplectic step (the impactor's loss is the body's external work).
TEST(Contact, RigidImpactorKeepsMomentumAndEnergyWithTheBody) {
  for (const char* shape : {"sphere", "cylinder"}) {
    DeckBuilder d;
    d.set("model.dimension", 2)
        .set("model.plane", "stress")
        .set("model.thickness", 0.01)
        .set("material.youngs_modulus", 72e9)
        .set("material.density", 2440.0)
        .set("discretization.spacing", 0.5e-3)
        .set("discretization.horizon_factor", 3.0)
        .set("discretization.body.box.min", {0.0, 0.0})
        .set("discretization.body.box.max", {0.02, 0.02})
        .set("damage.enabled", false)
        .set("solver.end_time", 1.5e-5);
    // 0.1 of the block's mass (9.8 g), 20 m/s, its face 0.2 mm from the block's left edge.
    DeckBuilder im;
    im.set("shape", shape).set("radius", 0.004).set("mass", 0.1 * 2440.0 * 0.02 * 0.02 * 0.01)
        .set("velocity", {20.0, 0.0});
    if (std::string(shape) == "sphere")
      im.set("center", {-0.0042, 0.01});
    else
      im.set("axis", {1.0, 0.0}).set("length", 0.01).set("center", {-0.0052, 0.01});
    d.append("impactors", im);
    const Deck dk = d.build("struck block");
    Model m = build_model(dk);
    const TimeStepChoice ts = choose_time_step(dk, m);
    VelocityVerlet vv(m, ts.dt);
    vv.initialize();
    auto momentum = [&]() {
      double p = m.impactors[0].mass * m.impactors[0].velocity[0];
      for (std::size_t i = 0; i < m.nodes.size(); ++i)
        p += m.nodes.density[i] * m.nodes.volume[i] * m.nodes.v[0][i];
      return p;
    };
    auto energy = [&]() {
      std::vector<double> W;
      return kinetic_energy(m.nodes) + strain_energy(m, W) + m.impactors[0].kinetic_energy();
    };
    const double p0 = momentum(), e0 = energy(), v0 = m.impactors[0].velocity[0];
    double worst_p = 0, worst_e = 0, worst_balance = 0;
    for (long s = 1; s <= ts.steps; ++s) {
      ASSERT_TRUE(vv.step());
      worst_p = std::max(worst_p, std::abs(momentum() - p0) / std::abs(p0));
      worst_e = std::max(worst_e, std::abs(energy() - e0) / e0);
      std::vector<double> W;
      const double balance = kinetic_energy(m.nodes) + strain_energy(m, W) - vv.external_work();
      worst_balance = std::max(worst_balance, std::abs(balance) / e0);
    }
    const double v_end = m.impactors[0].velocity[0];
    std::printf("%s: momentum %.3e, energy %.3e, balance %.3e, V_end/V0 %.4f\n", shape, worst_p,
                worst_e, worst_balance, v_end / v0);
    EXPECT_LT(worst_p, 1e-12) << shape;
    // Velocity Verlet's energy error: 0.09% (disk) and 0.72% (the flat face meets a whole column
    // of nodes at once) at the default step, 0.010% and 0.11% at half of it.
    EXPECT_LT(worst_e, 0.01) << shape;
    EXPECT_LT(worst_balance, 0.01) << shape;  // history.csv's balance column, the same energy
    // It struck: a light rigid body bounces back off the heavier block.
    EXPECT_LT(v_end, 0.0) << shape;
  }
}
