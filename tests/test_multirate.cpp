// Two-rate stepping (solver.multirate): the coarse nodes of a refined grid take 2 dt, the fine ones
// dt. Checked against single-rate Velocity-Verlet on the same refined grid: accuracy (second
// order in time), energy, the work saved, and the deck's refusal where forces are not row-local.
#include <gtest/gtest.h>

#include <cmath>

#include "adapt/adaptor.hpp"
#include "adapt/refine.hpp"
#include "analysis/energy.hpp"
#include "input/deck_builder.hpp"
#include "input/deck_error.hpp"
#include "solver/internal_forces.hpp"
#include "setup/build_model.hpp"
#include "solver/stable_time_step.hpp"
#include "solver/velocity_verlet.hpp"
#include "test_helpers.hpp"

using namespace periadapt;

namespace {

// A 40 mm x 20 mm glass plate (1 mm, m = 3) with a Gaussian bump of displacement at its centre.
DeckBuilder plate_deck() {
  const std::string bump = "exp(-((x-0.02)^2+(y-0.01)^2)/0.003^2)";
  DeckBuilder d = test::glass_plate({0.0, 0.0}, {0.04, 0.02});
  d
      .set("initial_conditions.displacement", test::Components{"1e-6*" + bump, "0.5e-6*" + bump})
      .set("damage.enabled", false)
      .set("solver.time_step", 1.0e-8)
      .set("solver.steps", 1);
  return d;
}

// The plate of `dk` with its left half refined to level 1 (0.5 mm, delta halved): the bump's
// waves cross the interface.
Model refined_plate(const Deck& dk) {
  Model m = build_model(dk);
  std::vector<std::uint32_t> parents;
  for (std::uint32_t i = 0; i < m.nodes.size(); ++i)
    if (m.nodes.x[0][i] < 0.02) parents.push_back(i);
  AdaptSpec spec;
  spec.max_level = 1;
  refine_nodes(m, parents, spec);
  return m;
}

Model refined_plate() { return refined_plate(plate_deck().build("bumped plate")); }

struct Outcome {
  std::vector<double> u;  // x then y displacement of every node at the end
  double energy_drift = 0, bond_evals = 0;
  std::size_t slow = 0;
};

Outcome run_plate(double dt, double t_end, bool multirate, double safety, int ratio = 2) {
  Model m = refined_plate();
  VelocityVerlet vv(m, dt);
  if (multirate) vv.set_multirate(safety, ratio);
  vv.initialize();
  std::vector<double> W;
  const double e0 = kinetic_energy(m.nodes) + strain_energy(m, W);
  const long steps = std::lround(t_end / dt);
  for (long s = 0; s < steps; ++s) EXPECT_TRUE(vv.step());
  Outcome r;
  r.energy_drift = (kinetic_energy(m.nodes) + strain_energy(m, W)) / e0 - 1.0;
  r.bond_evals = vv.bond_evaluations();
  r.slow = vv.slow_nodes();
  for (int d = 0; d < 2; ++d)
    for (std::size_t i = 0; i < m.nodes.size(); ++i)
      r.u.push_back(m.nodes.flags[i] & kActive ? m.nodes.u[d][i] : 0.0);
  return r;
}

// A multi-rate solver on the refined plate at 0.3 of its fine nodes' stable step, initialized.
VelocityVerlet plate_solver(Model& m, double safety, int ratio) {
  VelocityVerlet vv(m, 0.3 * stable_time_step(m).dt);
  vv.set_multirate(safety, ratio);
  vv.initialize();
  return vv;
}

double rel_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double num = 0, den = 0;
  for (std::size_t k = 0; k < a.size(); ++k) num += (a[k] - b[k]) * (a[k] - b[k]), den += b[k] * b[k];
  return std::sqrt(num / den);
}

}  // namespace

TEST(Multirate, CoarseNodesTakeTwiceTheStepAndTheRunStaysSecondOrderAccurate) {
  Model probe = refined_plate();
  const double dt_fine = stable_time_step(probe).dt;  // the fine nodes' Silling-Askari bound
  // dt = 0.3 of the fine bound: 2 dt is stable everywhere, so single-rate stepping at 2 dt is a
  // fair comparison; safety 0.5 keeps the fine nodes (2 dt = 0.6 of their bound) on dt and puts
  // the coarse ones (about 0.3 of theirs) on 2 dt. The reference is single-rate at dt / 8.
  const double dt = 0.3 * dt_fine, t_end = 600 * dt;
  const Outcome ref = run_plate(dt / 8, t_end, false, 0.5);
  const Outcome single = run_plate(dt, t_end, false, 0.5);
  const Outcome single2 = run_plate(2 * dt, t_end, false, 0.5);
  const Outcome two_rate = run_plate(dt, t_end, true, 0.5);
  // Half the step and half the safety: the same nodes on each rate, every step halved.
  const Outcome two_rate_half = run_plate(dt / 2, t_end, true, 0.25);
  const double e1 = rel_diff(single.u, ref.u), e2 = rel_diff(single2.u, ref.u);
  const double em = rel_diff(two_rate.u, ref.u), em_half = rel_diff(two_rate_half.u, ref.u);
  RecordProperty("error_single_dt", std::to_string(e1));
  RecordProperty("error_single_2dt", std::to_string(e2));
  RecordProperty("error_two_rate", std::to_string(em));
  RecordProperty("error_two_rate_half_dt", std::to_string(em_half));
  EXPECT_EQ(two_rate.slow, two_rate_half.slow);
  EXPECT_GT(two_rate.slow, 400u);  // at least the 20 x 20 coarse nodes
  // Between single-rate stepping at dt and at 2 dt ...
  EXPECT_GT(em, e1);
  EXPECT_LT(em, e2);
  // ... and second order: halving both steps divides the error by about 4.
  EXPECT_GT(em / em_half, 3.0);
  EXPECT_LT(em / em_half, 5.0);
  // Source-horizon pairing on a refined grid is not energy-conserving (ghost forces at the
  // interface; single-rate drift here about -3%): the second rate adds less than 0.5% to it.
  RecordProperty("energy_drift_single", std::to_string(single.energy_drift));
  RecordProperty("energy_drift_two_rate", std::to_string(two_rate.energy_drift));
  EXPECT_LT(std::abs(two_rate.energy_drift - single.energy_drift), 5e-3);
}

TEST(Multirate, ThreeRatesStaySecondOrderAccurate) {
  Model probe = refined_plate();
  const double dt_fine = stable_time_step(probe).dt;
  // The coarse nodes' bound is about twice the fine one: with safety 0.5 and dt = 0.3 of the fine
  // bound they take 3 dt (0.45 of their bound; 4 dt would be 0.6), the fine ones dt. Single-rate
  // stepping at 3 dt (0.9 of the fine bound) is still stable: the bracket of the check above.
  const double dt = 0.3 * dt_fine, t_end = 600 * dt;
  const Outcome ref = run_plate(dt / 8, t_end, false, 0.5);
  const Outcome single = run_plate(dt, t_end, false, 0.5);
  const Outcome single3 = run_plate(3 * dt, t_end, false, 0.5);
  const Outcome three = run_plate(dt, t_end, true, 0.5, 4);
  const Outcome three_half = run_plate(dt / 2, t_end, true, 0.25, 4);
  const double e1 = rel_diff(single.u, ref.u), e3 = rel_diff(single3.u, ref.u);
  const double em = rel_diff(three.u, ref.u), em_half = rel_diff(three_half.u, ref.u);
  RecordProperty("error_single_3dt", std::to_string(e3));
  RecordProperty("error_three_rate", std::to_string(em));
  RecordProperty("error_three_rate_half_dt", std::to_string(em_half));
  EXPECT_EQ(three.slow, three_half.slow);
  EXPECT_GT(three.slow, 400u);
  EXPECT_GT(em, e1);
  EXPECT_LT(em, e3);
  EXPECT_GT(em / em_half, 3.0);
  EXPECT_LT(em / em_half, 5.0);
  // Fewer bond sums than two rates (the count per cycle is checked exactly below).
  const Outcome two = run_plate(dt, t_end, true, 0.5, 2);
  RecordProperty("bond_evals_two_rate", std::to_string(two.bond_evals));
  RecordProperty("bond_evals_three_rate", std::to_string(three.bond_evals));
  EXPECT_LT(three.bond_evals, two.bond_evals);
  EXPECT_LT(std::abs(three.energy_drift - single.energy_drift), 5e-3);
}

namespace {

struct SyncErrors {
  double mid_cycle, synchronized;
  bool restored;
};

// Runs the refined plate on three rates to one step into a cycle of 3 steps and compares the slow
// nodes' velocities with the same run's own velocities at both ends of that cycle, interpolated
// linearly to the instant (so the error of the long step itself does not enter): before and
// after synchronize_velocities(); then checks that refresh() after an event that rebuilt no row
// gives them back.
SyncErrors sync_errors(double dt, double safety, int cycles) {
  Model mm = refined_plate(), me = refined_plate();
  VelocityVerlet multi(mm, dt), ends(me, dt);
  for (VelocityVerlet* vv : {&multi, &ends}) {
    vv->set_multirate(safety, 3);
    vv->initialize();
  }
  for (int s = 0; s < 3 * cycles; ++s) EXPECT_TRUE(ends.step());
  const auto v0 = me.nodes.v;
  for (int s = 0; s < 3; ++s) EXPECT_TRUE(ends.step());
  for (int s = 0; s < 3 * cycles + 1; ++s) EXPECT_TRUE(multi.step());
  std::vector<std::uint32_t> slow;
  for (std::uint32_t i = 0; i < mm.nodes.size(); ++i)
    if ((mm.nodes.flags[i] & kActive) && multi.rates()[i] == 3) slow.push_back(i);
  EXPECT_GT(slow.size(), 300u);
  auto v_error = [&]() {
    double num = 0, den = 0;
    for (std::uint32_t i : slow)
      for (int d = 0; d < 2; ++d) {
        const double now = (2 * v0[d][i] + me.nodes.v[d][i]) / 3;
        num += std::pow(mm.nodes.v[d][i] - now, 2);
        den += now * now;
      }
    return std::sqrt(num / den);
  };
  const auto v_before = mm.nodes.v;
  SyncErrors r{v_error(), 0, true};
  multi.synchronize_velocities();
  r.synchronized = v_error();
  const std::vector<std::uint32_t> none;  // an event that rebuilt no row
  multi.refresh(&none);
  for (std::uint32_t i : slow)
    for (int d = 0; d < 2; ++d)
      r.restored = r.restored && multi.rates()[i] == 3 &&
                   std::abs(mm.nodes.v[d][i] - v_before[d][i]) <= 1e-12 * std::abs(v_before[d][i]);
  return r;
}

}  // namespace

TEST(Multirate, EventsSeeTheVelocitiesOfOneInstant) {
  // Inside a 3 dt cycle a coarse node holds the velocity of its cycle's middle, half a step off:
  // a first-order error. synchronize_velocities() (called before every refinement event) removes
  // it: what is left is second order, a quarter when the step is halved, against a half before.
  const double dt = 0.3 * stable_time_step(refined_plate()).dt;
  const SyncErrors a = sync_errors(dt, 0.5, 100), b = sync_errors(dt / 2, 0.25, 200);
  RecordProperty("velocity_error_mid_cycle", std::to_string(a.mid_cycle));
  RecordProperty("velocity_error_synchronized", std::to_string(a.synchronized));
  RecordProperty("velocity_error_mid_cycle_half_dt", std::to_string(b.mid_cycle));
  RecordProperty("velocity_error_synchronized_half_dt", std::to_string(b.synchronized));
  EXPECT_TRUE(a.restored);
  EXPECT_TRUE(b.restored);
  EXPECT_LT(a.synchronized, a.mid_cycle);
  EXPECT_NEAR(a.mid_cycle / b.mid_cycle, 2.0, 0.5);
  EXPECT_GT(a.synchronized / b.synchronized, 3.0);
}

TEST(Multirate, TriggerEnergiesComeFromEachRowsOwnLatestPass) {
  // The energy trigger reads energy_density_recent(): the fast rows' densities of this very state,
  // the slow rows' those of their own latest pass (one step old here), with no extra pass.
  Model m = refined_plate();
  VelocityVerlet vv = plate_solver(m, 0.5, 2);
  for (int s = 0; s < 40; ++s) ASSERT_TRUE(vv.step());  // step 40 closes every 2 dt step
  std::vector<double> w_then, w_now;
  energy_density(m, w_then);
  ASSERT_TRUE(vv.step());  // step 41: the slow rows are idle
  energy_density(m, w_now);
  const std::vector<double>* recent = vv.energy_density_recent();
  ASSERT_NE(recent, nullptr);
  EXPECT_EQ(vv.energy_density_now(), nullptr);  // not this state's field: nobody asked for it
  double wmax = 0;
  for (double w : w_now) wmax = std::max(wmax, w);
  ASSERT_GT(wmax, 0.0);
  std::size_t slow = 0, differ = 0;
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    if (!(m.nodes.flags[i] & kActive)) continue;
    const bool is_slow = vv.rates()[i] == 2;
    EXPECT_NEAR((*recent)[i], is_slow ? w_then[i] : w_now[i], 1e-12 * wmax) << i;
    slow += is_slow;
    differ += is_slow && std::abs(w_then[i] - w_now[i]) > 1e-9 * wmax;
  }
  EXPECT_GT(slow, 400u);
  EXPECT_GT(differ, 100u);  // the one-step lag is visible: the check above is not vacuous
}

TEST(Multirate, DensitiesWrittenOnlyBeforeChecksEqualThoseOfEveryPass) {
  // With checks every 7 steps only the passes of the last max_ratio steps before each check
  // write densities: at the checks the field is bit for bit the one that every pass writing them
  // gives, also after rows changed (a refresh) between two checks; in between it is stale.
  Model ma = refined_plate(), mb = refined_plate();
  VelocityVerlet a = plate_solver(ma, 0.5, 4), b = plate_solver(mb, 0.5, 4);
  b.keep_energies_for_checks(7);  // 7: prime to every rate, so no window is longer than needed
  std::size_t compared = 0, stale = 0;
  for (long s = 1; s <= 60; ++s) {
    ASSERT_TRUE(a.step());
    ASSERT_TRUE(b.step());
    // Inside the window of check 28, after the rate-3 rows' pass (their latest before it): the
    // coarse rows right of x = 30 mm get softer, as an event would make them.
    if (s == 27)
      for (auto* p : {&ma, &mb}) {
        std::vector<std::uint32_t> rows;
        for (std::uint32_t i = 0; i < p->nodes.size(); ++i)
          if ((p->nodes.flags[i] & kActive) && p->nodes.x[0][i] > 0.03) rows.push_back(i);
        for (std::uint32_t i : rows) p->nodes.micromodulus[i] *= 0.7;
        (p == &ma ? a : b).synchronize_velocities();
        (p == &ma ? a : b).refresh(&rows);
      }
    const std::vector<double>* wa = a.energy_density_recent();
    const std::vector<double>* wb = b.energy_density_recent();
    ASSERT_NE(wa, nullptr);
    ASSERT_NE(wb, nullptr);
    for (std::size_t i = 0; i < ma.nodes.size(); ++i) {
      if (!(ma.nodes.flags[i] & kActive)) continue;
      if (s % 7 == 0) {
        EXPECT_EQ((*wa)[i], (*wb)[i]) << "step " << s << " node " << i;
        ++compared;
      } else if (s % 7 == 3) {
        stale += (*wa)[i] != (*wb)[i];
      }
    }
  }
  EXPECT_GT(compared, 8u * 1000u);
  EXPECT_GT(stale, 1000u);  // mid-way the plain sweeps left densities unwritten: not vacuous
  for (int k = 1; k <= 4; ++k) {  // every rate took part
    std::size_t c = 0;
    for (std::size_t i = 0; i < ma.nodes.size(); ++i) c += (ma.nodes.flags[i] & kActive) && a.rates()[i] == k;
    EXPECT_GT(c, 0u) << k;
  }
}

TEST(Multirate, EachRowIsSummedOncePerItsOwnStep) {
  // Rates 1 to 4 on one grid: over a cycle of 12 steps a row of rate k is summed 12 / k times.
  Model m = refined_plate();
  VelocityVerlet vv = plate_solver(m, 0.5, 4);
  std::array<double, 5> rows{};
  std::array<std::size_t, 5> count{};
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (m.nodes.flags[i] & kActive) {
      rows[vv.rates()[i]] += static_cast<double>(m.bonds.end(i) - m.bonds.begin(i));
      ++count[vv.rates()[i]];
    }
  for (int k = 1; k <= 4; ++k) EXPECT_GT(count[static_cast<std::size_t>(k)], 0u) << k;
  const double before = vv.bond_evaluations();
  for (int s = 0; s < 12; ++s) ASSERT_TRUE(vv.step());
  EXPECT_DOUBLE_EQ(vv.bond_evaluations() - before,
                   12 * rows[1] + 6 * rows[2] + 4 * rows[3] + 3 * rows[4]);
}

TEST(Multirate, SlowRowsAreSummedEveryOtherStepOnly) {
  Model m = refined_plate();
  VelocityVerlet vv = plate_solver(m, 0.5, 2);
  double all = 0, fast = 0;
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    if (!(m.nodes.flags[i] & kActive)) continue;
    const double row = static_cast<double>(m.bonds.end(i) - m.bonds.begin(i));
    all += row;
    if (vv.rates()[i] == 1) fast += row;
  }
  // Every slow node is on the coarse level; every fine node in the interior stays fast.
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if ((m.nodes.flags[i] & kActive) && vv.rates()[i] > 1) {
      const bool edge = m.nodes.x[0][i] < 0.001 || m.nodes.x[1][i] < 0.001 ||
                        m.nodes.x[1][i] > 0.019;
      EXPECT_TRUE(m.nodes.level[i] == 0 || edge) << i;
    }
  const double before = vv.bond_evaluations();
  for (int s = 0; s < 10; ++s) ASSERT_TRUE(vv.step());
  // Five steps sum the fast rows only, five sum every row.
  EXPECT_DOUBLE_EQ(vv.bond_evaluations() - before, 5 * fast + 5 * all);
  EXPECT_LT(fast, 0.9 * all);
}

TEST(Multirate, NodesWithPrescribedMotionsStayOnTheFineStep) {
  // The coarse right edge pulled at 1 m/s: its nodes would qualify for 2 dt but keep dt, so their
  // reactions (and the external work) are computed every step. The work done on the plate agrees
  // with single-rate stepping to the accuracy of the time integration (the displacements differ
  // by a few percent at this dt, see above; the work is an integral and agrees better).
  const Deck pulled =
      plate_deck()
          .append("boundary_conditions",
                  DeckBuilder()
                      .set("region", test::box({0.0395, 0.0}, {0.04, 0.02}))
                      .set("velocity", test::Components{"1.0", "0"}))
          .build("pulled plate");
  auto work = [&](bool multirate) {
    Model m = refined_plate(pulled);
    const double dt = 0.3 * stable_time_step(m).dt;
    VelocityVerlet vv(m, dt);
    if (multirate) vv.set_multirate(0.5);
    vv.initialize();
    if (multirate) {
      std::size_t driven = 0;
      for (const PrescribedMotion& pm : m.motions)
        for (std::uint32_t i : pm.nodes) {
          EXPECT_EQ(vv.rates()[i], 1) << i;
          ++driven;
        }
      EXPECT_GT(driven, 0u);
      EXPECT_GT(vv.slow_nodes(), 300u);
    }
    for (int s = 0; s < 600; ++s) EXPECT_TRUE(vv.step());
    return vv.external_work();
  };
  const double w1 = work(false), w2 = work(true);
  RecordProperty("external_work_single", std::to_string(w1));
  RecordProperty("external_work_two_rate", std::to_string(w2));
  EXPECT_GT(w1, 0.0);
  EXPECT_NEAR(w2 / w1, 1.0, 0.005);  // measured 0.07%
}

TEST(Multirate, DecksWhoseForcesAreNotRowLocalAreRefusedOthersAccepted) {
  // A 10 mm glass plate (PMB, or LPS with nu = 0.25); `stepped` adds an explicit solver section.
  auto plate = [](bool lps = false) {
    DeckBuilder d;
    d.set("model.dimension", 2).set("model.plane", "stress");
    if (lps) d.set("model.formulation", "lps").set("material.poisson_ratio", 0.25);
    d.set("material.youngs_modulus", 72.0e9)
        .set("material.density", 2440.0)
        .set("material.fracture_energy", 135.0)
        .set("discretization.spacing", 0.001)
        .set("discretization.horizon_factor", 3.0)
        .set("discretization.body.box.min", {0.0, 0.0})
        .set("discretization.body.box.max", {0.01, 0.01});
    return d;
  };
  auto stepped = [&](bool lps = false) {
    DeckBuilder d = plate(lps);
    d.set("solver.time_step", 1e-8).set("solver.steps", 1);
    return d;
  };
  auto key_of = [](const DeckBuilder& d) {
    try {
      d.build("multi-rate plate");
    } catch (const DeckError& e) {
      return e.key();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(key_of(stepped().set("solver.multirate", true)), "(accepted)");
  EXPECT_EQ(key_of(stepped(true).set("solver.multirate", true)), "solver.multirate");
  EXPECT_EQ(key_of(stepped()
                       .set("solver.multirate", true)
                       .set("solver.bond_pairing", "dual_horizon")),
            "solver.multirate");
  EXPECT_EQ(key_of(stepped()
                       .append("boundary_conditions",
                               DeckBuilder()
                                   .set("region", test::box({0.0, 0.0}, {0.001, 0.01}))
                                   .set("velocity", test::Components{"0", "0"}))
                       .set("solver.multirate", true)),
            "(accepted)");
  EXPECT_EQ(key_of(plate().set("solver.type", "static").set("solver.multirate", true)),
            "solver.multirate");
  EXPECT_EQ(key_of(stepped().set("solver.multirate", true).set("solver.multirate_ratio", 4)),
            "(accepted)");
  EXPECT_EQ(key_of(stepped().set("solver.multirate", true).set("solver.multirate_ratio", 5)),
            "solver.multirate_ratio");
  EXPECT_EQ(key_of(stepped().set("solver.multirate_ratio", 3)), "solver.multirate_ratio");
}

namespace {

// The velocity change that an "event" at t_e makes by the end of a 3 dt cycle: the rows of the
// coarse nodes right of x = 30 mm get a 30% softer micromodulus one step into the cycle
// (what rebuilding a row does to its forces; softer, so that they keep their rate), then the
// cycle runs out. Multi-rate run (rates up to
// 3) against single-rate stepping at dt / 16, both with and without the change, so that only the
// event's own effect is compared.
double event_effect_error(double dt) {
  auto run = [&](bool multi, bool change) {
    Model m = refined_plate();
    const double h = multi ? dt : dt / 16;
    const int sub = multi ? 1 : 16;
    VelocityVerlet vv(m, h);
    if (multi) vv.set_multirate(0.5 * dt / (0.3 * stable_time_step(m).dt), 3);
    vv.initialize();
    for (long s = 0; s < 3 * 40 * sub + sub; ++s) EXPECT_TRUE(vv.step());
    std::vector<std::uint32_t> rows;
    for (std::uint32_t i = 0; i < m.nodes.size(); ++i)
      if ((m.nodes.flags[i] & kActive) && m.nodes.level[i] == 0 && m.nodes.x[0][i] > 0.03 &&
          m.nodes.x[1][i] > 0.003 && m.nodes.x[1][i] < 0.017)
        rows.push_back(i);
    if (change) {
      vv.synchronize_velocities();
      for (std::uint32_t i : rows) m.nodes.micromodulus[i] *= 0.7;
      vv.refresh(&rows);
    }
    for (long s = 0; s < 2 * sub; ++s) EXPECT_TRUE(vv.step());
    if (multi) {
      for (std::uint32_t i : rows) EXPECT_EQ(vv.rates()[i], 3) << i;
    }
    std::vector<double> v;
    for (std::uint32_t i : rows)
      for (int d = 0; d < 2; ++d) v.push_back(m.nodes.v[d][i]);
    return v;
  };
  const auto mb = run(true, false), mc = run(true, true), rb = run(false, false), rc = run(false, true);
  std::vector<double> dm(mb.size()), dr(mb.size());
  for (std::size_t k = 0; k < mb.size(); ++k) dm[k] = mc[k] - mb[k], dr[k] = rc[k] - rb[k];
  return rel_diff(dm, dr);
}

}  // namespace

TEST(Multirate, ARowRebuiltInsideItsCycleRunsTheRestOfItUnderItsNewForces) {
  // Without taking the new acceleration into the rest of the cycle the event's effect is off by
  // a fixed fraction however small dt (a first-order error: 1/4 of it for a change one step into
  // a 3 dt cycle); with it the error falls with dt.
  const double dt = 0.3 * stable_time_step(refined_plate()).dt;
  const double e1 = event_effect_error(dt), e2 = event_effect_error(dt / 2);
  RecordProperty("event_effect_error", std::to_string(e1));
  RecordProperty("event_effect_error_half_dt", std::to_string(e2));
  EXPECT_LT(e1, 0.1);
  EXPECT_GT(e1 / e2, 1.6);
}
