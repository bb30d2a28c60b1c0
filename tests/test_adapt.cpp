// Adaptive grid refinement and scaling: conservation through a refinement event, equivalence of a
// fully refined grid with the grid built directly, bonds breaking only on the finest level.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>

#include "adapt/adaptor.hpp"
#include "adapt/refine.hpp"
#include "adapt/setup_zones.hpp"
#include "input/deck_builder.hpp"
#include "run/simulation.hpp"
#include "setup/build_model.hpp"
#include "solver/internal_forces.hpp"
#include "solver/velocity_verlet.hpp"
#include "analysis/energy.hpp"
#include "studies/wave_patch_2d.hpp"
#include "test_helpers.hpp"

using namespace periadapt;

namespace {

// A 30 x 16 mm glass plate with a pre-crack from its left edge.
DeckBuilder plate() {
  const std::vector<std::vector<double>> crack = {{0, 0.008}, {0.0121, 0.008}};
  DeckBuilder d = test::glass_plate({0.0, 0.0}, {0.03, 0.016});
  d
      .append("cracks", DeckBuilder().set("segment", crack))
      .set("solver.time_step", 5.0e-8)
      .set("solver.steps", 10);
  return d;
}

// A 10 deg lattice cut by a horizontal pre-crack through the middle of a 40 x 20 mm plate.
Deck rotated_cracked_plate() {
  const std::vector<std::vector<double>> crack = {{-0.015, 0.0}, {0.015, 0.0}};
  return DeckBuilder()
      .set("model.dimension", 2)
      .set("model.plane", "stress")
      .set("material.youngs_modulus", 72.0e9)
      .set("material.density", 2440.0)
      .set("material.fracture_energy", 135.0)
      .set("discretization.spacing", 0.001)
      .set("discretization.horizon_factor", 3.0)
      .set("discretization.rotation_deg", 10.0)
      .set("discretization.body.box.min", {-0.02, -0.01})
      .set("discretization.body.box.max", {0.02, 0.01})
      .append("cracks", DeckBuilder().set("segment", crack))
      .set("solver.time_step", 5.0e-8)
      .set("solver.steps", 10)
      .build("rotated lattice");
}

// A pre-cracked 40 mm x 20 mm glass plate pulled by edge tractions, with an adapt section.
DeckBuilder cracked_plate_deck(double traction, const DeckBuilder& adapt, int steps) {
  const std::vector<std::vector<double>> crack = {{0, 0.01}, {0.015, 0.01}};
  const DeckBuilder top = test::box({0.0, 0.019}, {0.04, 0.02});
  const DeckBuilder bottom = test::box({0.0, 0.0}, {0.04, 0.001});
  DeckBuilder d = test::glass_plate({0.0, 0.0}, {0.04, 0.02});
  d
      .append("cracks", DeckBuilder().set("segment", crack))
      .append("loads", DeckBuilder()
                           .set("type", "traction")
                           .set("region", top)
                           .set("value", {0.0, traction}))
      .append("loads", DeckBuilder()
                           .set("type", "traction")
                           .set("region", bottom)
                           .set("value", {0.0, -traction}))
      .append("damage.no_fail", top)
      .append("damage.no_fail", bottom)
      .set("adapt", adapt)
      .set("solver.time_step", 5.0e-8)
      .set("solver.steps", steps);
  return d;
}

// An adapt section that refines to level 1 (the callers add its triggers).
DeckBuilder level_one() {
  DeckBuilder a;
  a.set("max_level", 1);
  return a;
}

// A smooth, non-uniform velocity field, so that interpolation has gradients to carry.
void set_smooth_velocity(NodeSet& ns) {
  for (std::size_t i = 0; i < ns.size(); ++i) {
    ns.v[0][i] = 3.0 + std::sin(150.0 * ns.x[0][i]) * std::cos(90.0 * ns.x[1][i]);
    ns.v[1][i] = -2.0 + 40.0 * ns.x[0][i] * ns.x[1][i];
  }
}

std::vector<std::uint32_t> all_active(const Model& m) {
  std::vector<std::uint32_t> ids;
  for (std::uint32_t i = 0; i < m.nodes.size(); ++i)
    if (m.nodes.flags[i] & kActive) ids.push_back(i);
  return ids;
}

}  // namespace

namespace {

// Refines (method B) the block of nodes within 3 mm of (16, 10) mm, around the crack tip of
// cracked_plate_deck.
RefineStats refine_tip_block(Model& m) {
  std::vector<std::uint32_t> parents;
  for (std::uint32_t i = 0; i < m.nodes.size(); ++i)
    if (std::abs(m.nodes.x[0][i] - 0.016) < 0.003 && std::abs(m.nodes.x[1][i] - 0.01) < 0.003)
      parents.push_back(i);
  AdaptSpec spec;
  spec.enabled = true;
  return refine_nodes(m, parents, spec);
}

// A pre-cracked plate run 40 steps (energy densities asked for at the last), then a block of
// parents around the crack tip refined: where the partial-refresh tests start.
// `formulation`: pmb, or lps with glass's Poisson ratio.
DeckBuilder& with_formulation(DeckBuilder& d, const std::string& formulation) {
  d.set("model.formulation", formulation);
  if (formulation == "lps") d.set("material.poisson_ratio", 0.22);
  return d;
}

Deck tip_event_deck(const char* formulation) {
  DeckBuilder d = cracked_plate_deck(14e6, level_one().set("energy_trigger", 0.7), 40);
  return with_formulation(d, formulation).build("cracked plate");
}

// The largest difference between two fields over the largest magnitude of the second.
double relative_gap(const std::vector<double>& a, const std::vector<double>& b) {
  EXPECT_EQ(a.size(), b.size());
  double gap = 0, scale = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    gap = std::max(gap, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return scale > 0 ? gap / scale : gap;
}

struct TipEvent {
  Model m;
  VelocityVerlet vv{m, 5e-8};
  RefineStats st;
  bool energy_before_event = false;  // the step's pass computed the densities
  // `energy`: densities asked for at the event's step.
  explicit TipEvent(const char* formulation = "pmb", bool energy = true)
      : m(build_model(tip_event_deck(formulation))) {
    vv.initialize();
    if (energy) vv.request_energy_at(40);
    for (int s = 0; s < 40; ++s) EXPECT_TRUE(vv.step());
    energy_before_event = vv.energy_density_now() != nullptr;
    st = refine_tip_block(m);
  }
};

}  // namespace

TEST(Adapt, RefreshOfTheRebuiltRowsEqualsAFullForcePass) {
  // After an event, plain PMB recomputes only the forces of the rows the event rebuilt: every
  // other row has the same neighbours at the same positions. LPS also recomputes the rows within
  // a search radius of them, whose forces read the rebuilt rows' dilatations; the rest keep
  // theirs. The recomputed accelerations must equal, bit for bit, those of a full pass on a copy
  // of the model, and so must PMB's others. LPS's others come from the step's pass, which ran the
  // kernel without far-end factors (a uniform grid has none), and differ from the full pass's
  // only by the other instantiation's order of summation: round-off of the largest force.
  // (No bond has broken since the pre-crack: a bond broken in the last pass would change its
  // row's dilatation, which that pass's forces had not yet seen. No densities are asked for at
  // the event's step: LPS would take a full pass, next test.)
  for (const char* formulation : {"pmb", "lps"}) {
    TipEvent ev(formulation, false);
    const bool lps = std::string(formulation) == "lps";
    EXPECT_EQ(ev.vv.broken_bonds(), 0u) << formulation;
    ASSERT_LT(ev.st.rebuilt.size(), ev.m.nodes.size() / 2);  // a local event
    const std::vector<std::uint32_t> reading = rows_reading(ev.m, ev.st.rebuilt);
    if (lps) {
      EXPECT_GT(reading.size(), ev.st.rebuilt.size());
      EXPECT_LT(reading.size(), ev.m.nodes.size() / 2);
    } else {
      EXPECT_EQ(reading, ev.st.rebuilt);
    }
    Model full = ev.m;
    ev.vv.refresh(&ev.st.rebuilt);
    VelocityVerlet vv_full(full, 5e-8);
    vv_full.initialize();  // loads and forces of the whole model at the same state
    double scale = 0;
    for (std::size_t i = 0; i < full.nodes.size(); ++i)
      for (int d = 0; d < 2; ++d) scale = std::max(scale, std::abs(full.nodes.a[d][i]));
    std::size_t compared = 0;
    for (std::size_t i = 0; i < ev.m.nodes.size(); ++i) {
      if (!(ev.m.nodes.flags[i] & kActive)) continue;
      const bool recomputed = std::binary_search(reading.begin(), reading.end(), i);
      for (int d = 0; d < 2; ++d) {
        if (recomputed || !lps)
          EXPECT_EQ(ev.m.nodes.a[d][i], full.nodes.a[d][i]) << formulation << " node " << i;
        else
          EXPECT_NEAR(ev.m.nodes.a[d][i], full.nodes.a[d][i], 1e-14 * scale) << "node " << i;
      }
      ++compared;
    }
    EXPECT_GT(compared, 800u);
  }
}

TEST(Adapt, RefreshOfTheRebuiltRowsKeepsTheReactionsOfAFullPass) {
  // With prescribed motions an event's refresh also recomputes only the rebuilt rows; driven
  // nodes outside them keep their reactions. The left edge is driven with a ramped velocity (so
  // the reactions carry rho a), far from the refined block. Accelerations must equal those of a
  // full pass bit for bit, after a plain step and after an undone one (whose forces ns.f still
  // holds), and so must the next 20 steps and their external work (the refresh's reaction power
  // opens its trapezoid).
  // LPS as well (no bond breaks in these 40 steps).
  for (const char* formulation : {"pmb", "lps"})
  for (bool undo : {false, true}) {
    DeckBuilder driven = cracked_plate_deck(0.0, level_one().set("energy_trigger", 0.7), 60);
    driven.append("boundary_conditions",
                  DeckBuilder()
                      .set("name", "pull")
                      .set("region", test::box({0.0, 0.0}, {0.001, 0.02}))
                      .set("velocity", test::Components{"-4.0e5 * t", std::nullopt}));
    const Deck deck = with_formulation(driven, formulation).build("driven plate");
    struct Result {
      double work = 0;
      std::vector<double> a0, a1, u0;
    };
    auto run = [&](bool full) {
      Model m = build_model(deck);
      VelocityVerlet vv(m, 5e-8);
      vv.initialize();
      vv.set_undo(undo);
      for (int s = 0; s < 40; ++s) EXPECT_TRUE(vv.step());
      EXPECT_EQ(vv.broken_bonds(), 0u) << formulation;
      if (undo) vv.undo_last_step();
      const RefineStats st = refine_tip_block(m);
      for (std::uint32_t i : st.rebuilt) EXPECT_GT(m.nodes.x[0][i], 0.005) << "driven row rebuilt";
      vv.refresh(full ? nullptr : &st.rebuilt);
      Result r;
      r.a0 = m.nodes.a[0];
      r.a1 = m.nodes.a[1];
      for (int s = 0; s < 20; ++s) EXPECT_TRUE(vv.step());
      r.work = vv.external_work();
      r.u0 = m.nodes.u[0];
      return r;
    };
    const Result part = run(false), full = run(true);
    EXPECT_GT(std::abs(full.work), 0.0);
    if (std::string(formulation) == "pmb") {
      EXPECT_EQ(part.a0, full.a0) << "undo " << undo;
      EXPECT_EQ(part.a1, full.a1) << "undo " << undo;
      EXPECT_EQ(part.work, full.work) << "undo " << undo;
      EXPECT_EQ(part.u0, full.u0) << "undo " << undo;
    } else {
      // The rows LPS leaves hold the step pass's forces, which differ from the full pass's by
      // the kernel instantiation's order of summation (the previous test): round-off, which 20
      // steps carry but do not grow beyond a few orders.
      EXPECT_LT(relative_gap(part.a0, full.a0), 1e-14) << "undo " << undo;
      EXPECT_LT(relative_gap(part.a1, full.a1), 1e-14) << "undo " << undo;
      EXPECT_NEAR(part.work, full.work, 1e-12 * std::abs(full.work)) << "undo " << undo;
      EXPECT_LT(relative_gap(part.u0, full.u0), 1e-12) << "undo " << undo;
    }
  }
}

TEST(Adapt, EnergyDensitiesSurviveARowRefreshExactly) {
  // At a step whose energy densities were asked for, an event's partial refresh updates the
  // rebuilt rows' densities and keeps the others: the field must equal a fresh computation.
  // LPS's force pass forms the densities in another order than the energy pass, which a
  // distributed run's observers would take after a partial refresh: at such a step LPS refreshes
  // every row, and its field differs from the energy pass's by the same round-off as a step
  // pass's before any event.
  for (const char* formulation : {"pmb", "lps"}) {
    TipEvent ev(formulation);
    ASSERT_TRUE(ev.energy_before_event);
    ev.vv.refresh(&ev.st.rebuilt);
    const std::vector<double>* kept = ev.vv.energy_density_now();
    ASSERT_NE(kept, nullptr);
    std::vector<double> fresh;
    energy_density(ev.m, fresh);
    ASSERT_EQ(kept->size(), fresh.size());
    if (std::string(formulation) == "pmb") {
      for (std::size_t i = 0; i < fresh.size(); ++i) EXPECT_EQ((*kept)[i], fresh[i]) << "node " << i;
      continue;
    }
    // The extension r - x cancels: round-off grows by strain's inverse.
    Model m = build_model(tip_event_deck(formulation));
    VelocityVerlet vv{m, 5e-8};
    vv.initialize();
    vv.request_energy_at(40);
    for (int s = 0; s < 40; ++s) EXPECT_TRUE(vv.step());
    std::vector<double> step_fresh;
    energy_density(m, step_fresh);
    const double before = relative_gap(*vv.energy_density_now(), step_fresh);
    EXPECT_LT(before, 1e-11);
    // Twice the step pass's gap, or a few units of round-off where that gap is itself one (the
    // sanitizer build's -O1 rounds to 6e-17 before the event and 1.25e-16 after it).
    EXPECT_LE(relative_gap(*kept, fresh), std::max(2 * before, 1e-15));
  }
}

TEST(Adapt, RefinementConservesLinearMomentum) {
  Model m = build_model(plate().build("cracked plate"));
  NodeSet& ns = m.nodes;
  set_smooth_velocity(ns);
  AdaptSpec spec;
  spec.enabled = true;
  std::vector<std::uint32_t> parents;
  for (std::uint32_t i = 0; i < ns.size(); ++i)
    if (ns.x[0][i] > 0.008 && ns.x[0][i] < 0.02) parents.push_back(i);
  const RefineStats st = refine_nodes(m, parents, spec);
  EXPECT_EQ(st.children, 4 * parents.size());
  for (int d = 0; d < 2; ++d)
    EXPECT_NEAR(st.momentum_after[d], st.momentum_before[d],
                1e-12 * std::abs(st.momentum_before[d]));
  // Children carry the parent value plus a linear correction: kinetic energy grows by the
  // (small) energy of the resolved gradient, never decreases.
  EXPECT_GE(st.kinetic_after, st.kinetic_before * (1 - 1e-14));
  EXPECT_LT(st.kinetic_after - st.kinetic_before, 1e-3 * st.kinetic_before);
  RecordProperty("kinetic_energy_change_rel",
                 std::to_string((st.kinetic_after - st.kinetic_before) / st.kinetic_before));
}

TEST(Adapt, RefiningAMirrorSymmetricStateKeepsItSymmetric) {
  // A plate symmetric about y = 8 mm with a mirror-symmetric field (u_x, v_x even in y; u_y, v_y
  // odd), and a block of parents symmetric about that line: the children's interpolated fields
  // must be mirror images to round-off, whatever order the parents are processed in. (Fitting a
  // parent's gradient after its neighbours were switched off made the result order dependent:
  // the adaptive crack-branching run then grew asymmetric branches.)
  Model m = build_model(DeckBuilder()
                            .set("model.dimension", 2)
                            .set("model.plane", "stress")
                            .set("material.youngs_modulus", 72.0e9)
                            .set("material.density", 2440.0)
                            .set("material.fracture_energy", 135.0)
                            .set("discretization.spacing", 0.001)
                            .set("discretization.horizon_factor", 3.0)
                            .set("discretization.body.box.min", {0.0, 0.0})
                            .set("discretization.body.box.max", {0.03, 0.016})
                            .set("solver.time_step", 5.0e-8)
                            .set("solver.steps", 10)
                            .build("plate"));
  NodeSet& ns = m.nodes;
  const double yc = 0.008;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    const double x = ns.x[0][i], y = ns.x[1][i] - yc;
    ns.u[0][i] = 1e-6 * std::sin(200.0 * x) * std::cos(150.0 * y);
    ns.u[1][i] = 1e-6 * (40.0 * y + 3e4 * y * y * y) * (1 + 50.0 * x);
    ns.v[0][i] = 2.0 + std::cos(120.0 * x) * (1 + 1e4 * y * y);
    ns.v[1][i] = 300.0 * y * std::exp(30.0 * x);
    ns.sync_current(i);
  }
  std::vector<std::uint32_t> parents;
  for (std::uint32_t i = 0; i < ns.size(); ++i)
    if (ns.x[0][i] > 0.010 && ns.x[0][i] < 0.018 && std::abs(ns.x[1][i] - yc) < 0.004)
      parents.push_back(i);
  AdaptSpec spec;
  spec.enabled = true;
  const std::size_t n0 = ns.size();
  refine_nodes(m, parents, spec);
  std::map<std::pair<long, long>, std::size_t> at;
  for (std::size_t q = n0; q < ns.size(); ++q)
    at[{std::lround(ns.x[0][q] * 1e7), std::lround(ns.x[1][q] * 1e7)}] = q;
  ASSERT_EQ(at.size(), 4 * parents.size());
  double worst = 0;
  for (const auto& [key, q] : at) {
    const auto it = at.find({key.first, std::lround(2 * yc * 1e7) - key.second});
    ASSERT_NE(it, at.end());
    const std::size_t r = it->second;
    worst = std::max({worst, std::abs(ns.u[0][q] - ns.u[0][r]) / 1e-6,
                      std::abs(ns.u[1][q] + ns.u[1][r]) / 1e-6, std::abs(ns.v[0][q] - ns.v[0][r]),
                      std::abs(ns.v[1][q] + ns.v[1][r])});
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(Adapt, ChildrenAcrossAPreCrackTakeTheFieldOfTheirOwnFace) {
  // A 10 deg lattice cut by a horizontal pre-crack: where a lattice row crosses the crack line
  // (every dX / sin 10 deg = 5.8 mm), some sub-cell centres lie on the other side of the crack
  // from their parent. With the faces pulled apart (u_y, v_y = +-1 above / below the line) each
  // child must carry its own face's field; anchored at the parent it got the other face's and
  // tore its bonds apart on the next step. Momentum is kept to round-off either way.
  Model m = build_model(rotated_cracked_plate());
  NodeSet& ns = m.nodes;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    const double side = ns.x[1][i] > 0 ? 1.0 : -1.0;
    ns.u[1][i] = 1e-6 * side;
    ns.v[1][i] = side;
    ns.v[0][i] = 0.5;
    ns.sync_current(i);
  }
  // Parents well inside the crack's span: their visible families lie on one face only.
  std::vector<std::uint32_t> parents;
  for (std::uint32_t i = 0; i < ns.size(); ++i)
    if (std::abs(ns.x[0][i]) < 0.009 && std::abs(ns.x[1][i]) < 0.003) parents.push_back(i);
  const auto before = momentum_and_kinetic(ns);
  AdaptSpec spec;
  spec.enabled = true;
  const std::size_t n0 = ns.size();
  const RefineStats st = refine_nodes(m, parents, spec);
  ASSERT_EQ(st.children, 4 * parents.size());
  std::size_t across = 0;
  double worst = 0;
  for (std::size_t q = n0; q < ns.size(); ++q) {
    const double side = ns.x[1][q] > 0 ? 1.0 : -1.0;
    const std::size_t p = static_cast<std::size_t>(ns.parent[q]);
    if ((ns.x[1][p] > 0) != (side > 0)) ++across;
    worst = std::max({worst, std::abs(ns.u[1][q] / 1e-6 - side)});
  }
  EXPECT_GT(across, 0u);  // the geometry does put children across the line
  EXPECT_EQ(st.reanchored, across);
  EXPECT_LT(worst, 1e-9);
  // The velocity shift that restores momentum is tiny against the face velocity 1.
  for (std::size_t q = n0; q < ns.size(); ++q)
    EXPECT_NEAR(ns.v[1][q], ns.x[1][q] > 0 ? 1.0 : -1.0, 0.05);
  const auto after = momentum_and_kinetic(ns);
  for (int d = 0; d < 2; ++d)
    EXPECT_LT(std::abs(after.momentum[d] - before.momentum[d]), 1e-12 * before.momentum_scale);
}

TEST(Adapt, MethodAKeepsVolumeAndMomentumAndCutsInterfaceCellsByEq34) {
  // A 6 x 6 block of 1 mm parents refined by method A: the 13 x 13 half-spacing lattice over it
  // (169 - 36 = 133 new nodes, the parents kept), total volume unchanged, and the coarse
  // neighbours reduced by the overlap of the new cells: V_c - V_f for a side neighbour (j = 3 in
  // Eq. 3.4), V_c - V_f / 4 for a corner-diagonal one (j = 1), with V_f = V_c / 4.
  Model m = build_model(plate().build("cracked plate"));
  NodeSet& ns = m.nodes;
  set_smooth_velocity(ns);
  auto total_volume = [&] {
    double v = 0;
    for (std::size_t i = 0; i < ns.size(); ++i)
      if (ns.flags[i] & kActive) v += ns.volume[i];
    return v;
  };
  auto node_at = [&](double x, double y) {
    for (std::size_t i = 0; i < ns.size(); ++i)
      if (std::hypot(ns.x[0][i] - x, ns.x[1][i] - y) < 1e-9) return i;
    return ns.size();
  };
  const double v0 = total_volume(), vc = 1e-6;
  AdaptSpec spec;
  spec.enabled = true;
  spec.method = NodeGeneration::A;
  std::vector<std::uint32_t> parents;
  for (std::uint32_t i = 0; i < ns.size(); ++i)
    if (ns.x[0][i] > 0.010 && ns.x[0][i] < 0.016 && ns.x[1][i] > 0.004 && ns.x[1][i] < 0.010)
      parents.push_back(i);
  ASSERT_EQ(parents.size(), 36u);
  const std::size_t n0 = ns.size();
  const RefineStats st = refine_nodes(m, parents, spec);
  EXPECT_EQ(st.children, 133u);
  EXPECT_EQ(ns.size(), n0 + 133);
  EXPECT_NEAR(total_volume(), v0, 1e-12 * v0);
  for (std::uint32_t p : parents) {
    EXPECT_TRUE(ns.flags[p] & kActive);
    EXPECT_EQ(ns.level[p], 1);
    EXPECT_NEAR(ns.volume[p], vc / 4, 1e-18);
  }
  const std::size_t side = node_at(0.0095, 0.0075), corner = node_at(0.0095, 0.0035),
                    far = node_at(0.0075, 0.0075);
  ASSERT_LT(side, n0);
  ASSERT_LT(corner, n0);
  EXPECT_NEAR(ns.volume[side], vc - vc / 4, 1e-18);
  EXPECT_NEAR(ns.volume[corner], vc - vc / 16, 1e-18);
  EXPECT_NEAR(ns.volume[far], vc, 1e-18);
  EXPECT_NEAR(ns.volume[node_at(0.010, 0.0075)], vc / 4, 1e-18);  // a new mid-point
  for (int d = 0; d < 2; ++d)
    EXPECT_NEAR(st.momentum_after[d], st.momentum_before[d], 1e-12 * std::abs(st.momentum_before[d]));
  RecordProperty("kinetic_energy_change_rel",
                 std::to_string((st.kinetic_after - st.kinetic_before) / st.kinetic_before));
  EXPECT_LT(std::abs(st.kinetic_after - st.kinetic_before), 1e-3 * st.kinetic_before);
}

TEST(Adapt, FullyRefinedGridEqualsTheGridBuiltDirectly) {
  // Refining every node once with delta-scaling must give exactly the level-1 grid: same nodes,
  // volumes, horizons, micromoduli, critical stretches, bonds (pre-crack included), and the same
  // motion up to summation order.
  Model a = build_model(plate().build("cracked plate"));
  AdaptSpec spec;
  spec.enabled = true;
  refine_nodes(a, all_active(a), spec);
  Model b = build_model(plate().set("discretization.spacing", 0.0005).build("fine cracked plate"));
  const auto ia = all_active(a), ib = all_active(b);
  ASSERT_EQ(ia.size(), ib.size());
  auto key = [](const NodeSet& ns, std::uint32_t i) {
    return std::make_pair(std::llround(ns.x[0][i] * 1e7), std::llround(ns.x[1][i] * 1e7));
  };
  std::map<std::pair<long long, long long>, std::uint32_t> pos_b;
  for (std::uint32_t i : ib) pos_b[key(b.nodes, i)] = i;
  std::size_t broken_a = 0, broken_b = 0, bonds_a = 0, bonds_b = 0;
  for (std::uint32_t i : ia) {
    auto it = pos_b.find(key(a.nodes, i));
    ASSERT_NE(it, pos_b.end()) << "child at " << a.nodes.x[0][i] << ", " << a.nodes.x[1][i];
    const std::uint32_t j = it->second;
    EXPECT_NEAR(a.nodes.volume[i], b.nodes.volume[j], 1e-15);
    EXPECT_NEAR(a.nodes.horizon[i], b.nodes.horizon[j], 1e-15);
    EXPECT_NEAR(a.nodes.micromodulus[i] / b.nodes.micromodulus[j], 1.0, 1e-12);
    EXPECT_NEAR(a.nodes.critical_stretch[i] / b.nodes.critical_stretch[j], 1.0, 1e-12);
    EXPECT_EQ(a.bonds.end(i) - a.bonds.begin(i), b.bonds.end(j) - b.bonds.begin(j));
    EXPECT_NEAR(a.nodes.damage(i), b.nodes.damage(j), 1e-12);
    for (std::uint64_t k = a.bonds.begin(i); k < a.bonds.end(i); ++k)
      broken_a += !BondFamilies::intact(a.bonds.beta[k]);
    for (std::uint64_t k = b.bonds.begin(j); k < b.bonds.end(j); ++k)
      broken_b += !BondFamilies::intact(b.bonds.beta[k]);
    bonds_a += a.bonds.end(i) - a.bonds.begin(i);
    bonds_b += b.bonds.end(j) - b.bonds.begin(j);
  }
  EXPECT_EQ(bonds_a, bonds_b);
  EXPECT_EQ(broken_a, broken_b);
  EXPECT_GT(broken_a, 0u);

  // Same motion: a sudden opening velocity across the crack, 40 steps.
  for (Model* m : {&a, &b})
    for (std::size_t i = 0; i < m->nodes.size(); ++i)
      if (m->nodes.flags[i] & kActive) m->nodes.v[1][i] = m->nodes.x[1][i] > 0.008 ? 2.0 : -2.0;
  VelocityVerlet va(a, 2.5e-8), vb(b, 2.5e-8);
  va.initialize();
  vb.initialize();
  for (int s = 0; s < 40; ++s) {
    ASSERT_TRUE(va.step());
    ASSERT_TRUE(vb.step());
  }
  double worst = 0, scale = 0;
  for (std::uint32_t i : ia) {
    const std::uint32_t j = pos_b[key(a.nodes, i)];
    for (int d = 0; d < 2; ++d) {
      worst = std::max(worst, std::abs(a.nodes.u[d][i] - b.nodes.u[d][j]));
      scale = std::max(scale, std::abs(b.nodes.u[d][j]));
    }
  }
  EXPECT_LT(worst, 1e-9 * scale);
}

// Bodies whose boundary cuts the lattice (a hole, a disk, a rotated box): with
// adapt.fill_boundary_cells, refining every node once gives the uniform fine grid's nodes,
// volumes and families, including the nodes in sub-cells of coarse cells that have no node
// (their centres lie outside the body). Without it the refined body keeps the coarse staircase,
// whose corners the fine nodes resolve as re-entrant corners: a level-2 zone beside a hole then
// cracks at those corners under a load the uniform finest grid carries (docs/agrs.md).
TEST(Adapt, FullyRefinedCurvedBodiesEqualTheirFineGrids) {
  // Glass plates (test_helpers.hpp) with other bodies; 10 steps of 50 ns.
  auto base = [](std::initializer_list<double> lo, std::initializer_list<double> hi, double h) {
    DeckBuilder d = test::glass_plate(lo, hi);
    d.set("discretization.spacing", h).set("solver.time_step", 5.0e-8).set("solver.steps", 10);
    return d;
  };
  auto holed = [&](double h) {
    return base({0.0, 0.0}, {0.03, 0.03}, h)
        .append("discretization.holes",
                DeckBuilder().set("disk.center", {0.015, 0.015}).set("disk.radius", 0.0053))
        .build("plate with a hole");
  };
  auto disk = [&](double h) {
    return base({0.0, 0.0}, {0.0, 0.0}, h)
        .set("discretization.body",
             DeckBuilder().set("disk.center", {0.0, 0.0}).set("disk.radius", 0.0117))
        .build("disk");
  };
  auto rotated = [&](double h) {
    return base({-0.01, -0.006}, {0.01, 0.006}, h)
        .set("discretization.rotation_deg", 17.0)
        .build("rotated box");
  };
  for (auto make : {std::function<Deck(double)>(holed), std::function<Deck(double)>(disk),
                    std::function<Deck(double)>(rotated)}) {
    const Model b = build_model(make(0.0005));
    AdaptSpec spec;
    spec.enabled = true;
    Model plain = build_model(make(0.001));
    EXPECT_EQ(refine_nodes(plain, all_active(plain), spec).fillers, 0u);
    EXPECT_LT(all_active(plain).size(), all_active(b).size());  // the coarse staircase
    spec.fill_boundary_cells = true;
    Model a = build_model(make(0.001));
    const RefineStats st = refine_nodes(a, all_active(a), spec);
    EXPECT_GT(st.fillers, 0u);
    const auto ia = all_active(a), ib = all_active(b);
    auto key = [](const NodeSet& ns, std::uint32_t i) {
      return std::make_pair(std::llround(ns.x[0][i] * 1e7), std::llround(ns.x[1][i] * 1e7));
    };
    std::map<std::pair<long long, long long>, std::uint32_t> pos_b;
    for (std::uint32_t i : ib) pos_b[key(b.nodes, i)] = i;
    std::size_t matched = 0, same_family = 0;
    for (std::uint32_t i : ia) {
      const auto it = pos_b.find(key(a.nodes, i));
      if (it == pos_b.end()) continue;
      ++matched;
      const std::uint32_t j = it->second;
      same_family += a.bonds.end(i) - a.bonds.begin(i) == b.bonds.end(j) - b.bonds.begin(j);
      EXPECT_NEAR(a.nodes.volume[i], b.nodes.volume[j], 1e-12 * b.nodes.volume[j]);
    }
    EXPECT_EQ(ia.size(), ib.size());
    EXPECT_EQ(matched, ib.size());
    EXPECT_EQ(same_family, ib.size());
  }
}

TEST(Adapt, ABodyInUniformMotionKeepsItsVelocityThroughFillersAndReanchoredChildren) {
  // The rotated lattice's staircase edges are filled (fillers bring mass, boundary cells lose
  // what lay outside the body) and the pre-crack re-anchors children: in a uniform velocity
  // field every new node must move with the body, the momentum changing only by the mass the
  // fine grid's volumes add or remove.
  Model m = build_model(rotated_cracked_plate());
  const double v0[2] = {1.5, -0.7};
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    for (int d = 0; d < 2; ++d) m.nodes.v[d][i] = v0[d];
  AdaptSpec spec;
  spec.enabled = true;
  spec.fill_boundary_cells = true;
  const RefineStats st = refine_nodes(m, all_active(m), spec);
  EXPECT_GT(st.fillers, 0u);
  EXPECT_GT(st.reanchored, 0u);
  double worst = 0, mass = 0;
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (m.nodes.flags[i] & kActive) {
      mass += m.nodes.density[i] * m.nodes.volume[i];
      for (int d = 0; d < 2; ++d) worst = std::max(worst, std::abs(m.nodes.v[d][i] - v0[d]));
    }
  EXPECT_LT(worst, 1e-12);
  for (int d = 0; d < 2; ++d) EXPECT_NEAR(st.momentum_after[d], mass * v0[d], 1e-12 * mass);
}

TEST(Adapt, WithTheDamageTriggerBondsBreakOnlyOnTheFinestLevel) {
  // A pre-cracked plate pulled hard: every bond that the dynamics breaks must belong to nodes
  // that could not be refined further (the step is undone and redone after refining).
  const Deck dk = cracked_plate_deck(60.0e6, level_one().set("damage_trigger", true), 200)
                      .build("cracked plate");
  Model m = build_model(dk);
  const std::size_t n0 = m.nodes.size();
  VelocityVerlet vv(m, 5.0e-8);
  vv.initialize();
  Adaptor ad(m, vv, dk.adapt);
  for (int s = 0; s < 200; ++s) ASSERT_TRUE(ad.step());
  ASSERT_FALSE(ad.events().empty());
  const NodeSet& ns = m.nodes;
  std::size_t dynamic_breaks = 0, coarse_breaks = 0;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    for (std::uint64_t k = m.bonds.begin(i); k < m.bonds.end(i); ++k) {
      if (BondFamilies::intact(m.bonds.beta[k])) continue;
      const std::uint32_t j = m.bonds.neighbor[k];
      const Vec3 xi{ns.x[0][i], ns.x[1][i], 0}, xj{ns.x[0][j], ns.x[1][j], 0};
      if (bond_crosses_segment(xi, xj, m.cracks[0].points[0], m.cracks[0].points[1])) continue;
      ++dynamic_breaks;
      if (ns.level[i] == 0 && i < n0 && !(ns.flags[i] & kNoFail)) ++coarse_breaks;
    }
  }
  EXPECT_GT(dynamic_breaks, 0u) << "the crack must have grown";
  EXPECT_EQ(coarse_breaks, 0u);
  RecordProperty("nodes_added", std::to_string(ad.nodes_added()));
}

#include "solver/linear_static.hpp"

TEST(Adapt, DualHorizonPairingRemovesTheGhostForceOfScaledHorizons) {
  // Half a plate refined once (delta halved, micromodulus rescaled): under a uniform strain the
  // bonds of the interface carry different micromoduli in their two directions. With source-
  // horizon pairing the internal forces no longer sum to zero (ghost forces, momentum is not
  // conserved); with dual-horizon pairing they cancel to round-off.
  Model m = build_model(
      DeckBuilder()
          .set("model.dimension", 2)
          .set("model.plane", "stress")
          .set("material.youngs_modulus", 1.0e9)
          .set("material.density", 1000.0)
          .set("discretization.spacing", 0.01)
          .set("discretization.horizon_factor", 3.0)
          .set("discretization.quadrature", "ipa_hybrid")
          .set("discretization.body.box.min", {0.0, 0.0})
          .set("discretization.body.box.max", {0.4, 0.2})
          .append("adapt.initial_refinement",
                  DeckBuilder().set("region", test::box({0.0, 0.0}, {0.195, 0.2})).set("level", 1))
          .set("damage.enabled", false)
          .set("solver.type", "static")
          .build("half-refined plate"));
  const NodeSet& ns = m.nodes;
  std::size_t fine = 0;
  for (std::size_t i = 0; i < ns.size(); ++i) fine += (ns.flags[i] & kActive) && ns.level[i] == 1;
  ASSERT_GT(fine, 0u);
  const Eigen::Index n2 = static_cast<Eigen::Index>(2 * ns.size());
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n2);
  for (std::size_t i = 0; i < ns.size(); ++i) {
    u[static_cast<Eigen::Index>(2 * i)] = 1e-3 * ns.x[0][i] + 4e-4 * ns.x[1][i];
    u[static_cast<Eigen::Index>(2 * i + 1)] = -3e-4 * ns.x[1][i];
  }
  double net[2][2] = {{0, 0}, {0, 0}}, scale[2] = {0, 0};
  int v = 0;
  for (BondPairing p : {BondPairing::SourceHorizon, BondPairing::DualHorizon}) {
    const auto K = assemble_bond_stiffness(ns, m.bonds, m.material.shape, p);
    const Eigen::VectorXd f = K * u;  // minus the internal force density
    for (std::size_t i = 0; i < ns.size(); ++i) {
      if (!(ns.flags[i] & kActive)) continue;
      for (int d = 0; d < 2; ++d) {
        const double fi = f[static_cast<Eigen::Index>(2 * i + d)] * ns.volume[i];
        net[v][d] += fi;
        scale[v] += std::abs(fi);
      }
    }
    ++v;
  }
  const double ghost = std::hypot(net[0][0], net[0][1]) / scale[0];
  const double dual = std::hypot(net[1][0], net[1][1]) / scale[1];
  EXPECT_GT(ghost, 1e-3) << "source pairing should show the ghost-force imbalance";
  EXPECT_LT(dual, 1e-12);
  RecordProperty("ghost_force_imbalance_source", std::to_string(ghost));
  RecordProperty("ghost_force_imbalance_dual", std::to_string(dual));
}

#include "adapt/coarsen.hpp"

TEST(Adapt, RefiningToLevelTwoAndCoarseningBackRestoresTheGrid) {
  // A zone refined twice and coarsened twice must give back the original active nodes and bond
  // families exactly (positions, volumes, horizons, quadrature factors, pre-crack cuts), and
  // every coarsening must keep linear momentum.
  Model m = build_model(plate().build("cracked plate"));
  NodeSet& ns = m.nodes;
  for (std::size_t i = 0; i < ns.size(); ++i) ns.v[0][i] = 1.0 + ns.x[1][i];
  using Bond = std::tuple<long long, long long, long long, long long, float>;
  auto snapshot = [&]() {
    std::vector<Bond> bonds;
    for (std::size_t i = 0; i < ns.size(); ++i) {
      if (!(ns.flags[i] & kActive)) continue;
      for (std::uint64_t k = m.bonds.begin(i); k < m.bonds.end(i); ++k) {
        const std::uint32_t j = m.bonds.neighbor[k];
        bonds.emplace_back(std::llround(ns.x[0][i] * 1e7), std::llround(ns.x[1][i] * 1e7),
                           std::llround(ns.x[0][j] * 1e7), std::llround(ns.x[1][j] * 1e7),
                           m.bonds.beta[k]);
      }
    }
    std::sort(bonds.begin(), bonds.end());
    return bonds;
  };
  const auto before = snapshot();
  AdaptSpec spec;
  spec.enabled = true;
  spec.max_level = 2;
  auto in_zone = [&](std::size_t i) {
    return (ns.flags[i] & kActive) && ns.x[0][i] > 0.01 && ns.x[0][i] < 0.02;
  };
  for (int level = 0; level < 2; ++level) {
    std::vector<std::uint32_t> ids;
    for (std::uint32_t i = 0; i < ns.size(); ++i)
      if (in_zone(i) && ns.level[i] == level) ids.push_back(i);
    ASSERT_FALSE(ids.empty());
    refine_nodes(m, ids, spec);
  }
  EXPECT_NE(snapshot(), before);
  for (int pass = 0; pass < 2; ++pass) {
    const auto parents = coarsenable_parents(m);
    ASSERT_FALSE(parents.empty());
    const RefineStats st = coarsen_nodes(m, parents);
    for (int d = 0; d < 2; ++d)
      EXPECT_NEAR(st.momentum_after[d], st.momentum_before[d],
                  1e-12 * std::abs(st.momentum_before[d]));
  }
  EXPECT_TRUE(coarsenable_parents(m).empty());
  EXPECT_EQ(snapshot(), before);
}

TEST(Adapt, DualHorizonDynamicsConservesMomentumOnARefinedGrid) {
  // Half a free plate refined once; a non-uniform initial velocity; 60 explicit steps. The dual-
  // horizon form keeps total linear momentum to round-off, the plain form does not (ghost forces).
  double drift[2] = {0, 0};
  int v = 0;
  for (const char* pairing : {"source_horizon", "dual_horizon"}) {
    const Deck dk =
        DeckBuilder()
            .set("model.dimension", 2)
            .set("model.plane", "stress")
            .set("material.youngs_modulus", 72.0e9)
            .set("material.density", 2440.0)
            .set("material.fracture_energy", 135.0)
            .set("discretization.spacing", 0.001)
            .set("discretization.horizon_factor", 3.0)
            .set("discretization.body.box.min", {0.0, 0.0})
            .set("discretization.body.box.max", {0.03, 0.016})
            .set("initial_conditions.velocity", test::Components{"5*sin(200*x)", "3*cos(150*y)"})
            .append("adapt.initial_refinement",
                    DeckBuilder()
                        .set("region", test::box({0.0, 0.0}, {0.0145, 0.016}))
                        .set("level", 1))
            .set("solver.time_step", 2.0e-8)
            .set("solver.steps", 60)
            .set("solver.bond_pairing", pairing)
            .build("half-refined plate");
    Model m = build_model(dk);
    drift[v++] = test::momentum_drift(m, 2e-8, 60);
  }
  EXPECT_GT(drift[0], 1e-9) << "the plain form should show the ghost-force drift";
  EXPECT_LT(drift[1], 1e-12);
  RecordProperty("momentum_drift_source", std::to_string(drift[0]));
  RecordProperty("momentum_drift_dual", std::to_string(drift[1]));
}

#include <cstdlib>

TEST(Adapt, LocalFamilyRebuildEqualsTheGlobalOne) {
  // Refinement rebuilds only the families within reach of the changed nodes; a run with the
  // whole model rebuilt at every event (PERIADAPT_GLOBAL_REBUILD) must give the same state.
  const DeckBuilder deck = cracked_plate_deck(
      40.0e6, level_one().set("energy_trigger", 0.5).set("damage_trigger", true), 150);
  std::vector<double> result[2];
  for (int global = 0; global < 2; ++global) {
    if (global) setenv("PERIADAPT_GLOBAL_REBUILD", "1", 1);
    else unsetenv("PERIADAPT_GLOBAL_REBUILD");
    const Deck dk = deck.build("cracked plate");
    Model m = build_model(dk);
    VelocityVerlet vv(m, 5.0e-8);
    vv.initialize();
    Adaptor ad(m, vv, dk.adapt);
    for (int s = 0; s < 150; ++s) ASSERT_TRUE(ad.step());
    ASSERT_FALSE(ad.events().empty());
    for (std::size_t i = 0; i < m.nodes.size(); ++i) {
      result[global].push_back(m.nodes.u[1][i]);
      result[global].push_back(m.nodes.damage(i));
    }
  }
  unsetenv("PERIADAPT_GLOBAL_REBUILD");
  ASSERT_EQ(result[0].size(), result[1].size());
  // Displacements bit for bit; damage to round-off (rows the local rebuild copies keep their
  // running broken-bond sums, the global rebuild sums them afresh).
  for (std::size_t k = 0; k < result[0].size(); k += 2) {
    ASSERT_EQ(result[0][k], result[1][k]) << k;
    ASSERT_NEAR(result[0][k + 1], result[1][k + 1], 1e-12) << k;
  }
}

namespace {

// Bobaru 6.2.2's bar [0, 450] (triangular micromodulus, sub-cell quadrature) and its Gaussian.
DeckBuilder pulse_bar(double spacing, double horizon) {
  DeckBuilder d;
  d.set("model.dimension", 1)
      .set("material.youngs_modulus", 1.0)
      .set("material.density", 1.0)
      .set("material.micromodulus", "triangular")
      .set("discretization.spacing", spacing)
      .set("discretization.horizon", horizon)
      .set("discretization.registration", "node_on_edge")
      .set("discretization.quadrature", "subcell")
      .set("discretization.body.box.min", {0.0})
      .set("discretization.body.box.max", {450.0})
      .set("initial_conditions.displacement", test::Components{"0.02*exp(-0.01*x^2)"})
      .set("damage.enabled", false);
  return d;
}

// A refined zone that follows the pulse: level 1, total-energy trigger at 75%, six horizons of
// visibility, coarsening.
DeckBuilder moving_zone() {
  DeckBuilder a = level_one();
  a.set("energy_trigger", 0.75)
      .set("energy", "total")
      .set("coarsen", true)
      .set("visibility_factor", 6);
  return a;
}

}  // namespace

TEST(Adapt, RefinedZoneStaysAroundATravellingPulse) {
  // Bobaru 6.2.2: total-energy trigger at 75%, six horizons of visibility. Hot nodes that are
  // already refined still ask for the coarse nodes around them (thesis Fig. 3.4), so the refined
  // zone moves with the pulse and covers it on both sides; a zone that only grows from coarse hot
  // nodes trails behind the peak.
  const Deck dk = pulse_bar(1.0, 3.0)
                      .set("solver.end_time", 200.0)
                      .set("solver.time_step", 0.25)
                      .set("solver.bond_pairing", "dual_horizon")
                      .set("adapt", moving_zone())
                      .build("Bobaru bar");
  Model m = build_model(dk);
  VelocityVerlet vv(m, 0.25);
  vv.initialize();
  Adaptor ad(m, vv, dk.adapt);
  for (int s = 0; s < 800; ++s) ASSERT_TRUE(ad.step());
  const NodeSet& ns = m.nodes;
  std::size_t peak = 0;
  double lo = INFINITY, hi = -INFINITY;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    if (ns.u[0][i] > ns.u[0][peak]) peak = i;
    if (ns.level[i] > 0) lo = std::min(lo, ns.x[0][i]), hi = std::max(hi, ns.x[0][i]);
  }
  const double xp = ns.x[0][peak];
  EXPECT_NEAR(xp, 200.0, 20.0);  // the pulse has travelled at c = 1 (less a little dispersion)
  // The pulse's energy sits within about 10 of its peak; the zone reaches 6 coarse horizons
  // (18) beyond the hot nodes on both sides.
  EXPECT_LT(lo, xp - 15.0);
  EXPECT_GT(hi, xp + 15.0);
}

TEST(Adapt, EnergyConservingEventsStopTheMovingZoneFromPumpingEnergy) {
  // The Bobaru pulse on the 2,701-node grid with a refined zone following it: every event
  // changes K + U a little and the front interface sits in more energetic field than the rear
  // one, so the total energy climbs (+8.4% by t = 100, +46% by t = 200); with
  // adapt.conserve_energy the rebuilt rows give back what each event changed (+0.36%).
  auto drift = [](bool conserve) {
    const Deck dk = pulse_bar(0.16666666666666666, 1.5)
                        .set("solver.end_time", 100.0)
                        .set("solver.time_step", 0.041666666666666664)
                        .set("solver.bond_pairing", "dual_horizon")
                        .set("adapt", moving_zone().set("conserve_energy", conserve))
                        .build("Bobaru bar");
    Model m = build_model(dk);
    VelocityVerlet vv(m, *dk.time_step);
    vv.initialize();
    Adaptor ad(m, vv, dk.adapt);
    std::vector<double> W;
    const double e0 = kinetic_energy(m.nodes) + strain_energy(m, W);
    for (int s = 0; s < 2400; ++s) EXPECT_TRUE(ad.step());
    EXPECT_GT(ad.events().size(), 100u);
    return (kinetic_energy(m.nodes) + strain_energy(m, W)) / e0 - 1.0;
  };
  const double plain = drift(false), conserved = drift(true);
  RecordProperty("energy_drift_plain", std::to_string(plain));
  RecordProperty("energy_drift_conserving", std::to_string(conserved));
  EXPECT_GT(plain, 0.05);
  EXPECT_LT(std::abs(conserved), 0.01);
}

TEST(Adapt, RefinementIn3DKeepsACrackThatWasNotAPreCrack) {
  // A 3D block cut in two by broken bonds across z = 4 mm (broken during a run, not a pre-crack,
  // so nothing re-cuts them): refining every node must not heal the cut. The broken bonds leave
  // small squares across themselves (crack facets); a child bond that passes through one starts
  // broken. Without facets every child bond across the plane would be intact.
  Model m = build_model(DeckBuilder()
                            .set("model.dimension", 3)
                            .set("material.youngs_modulus", 72.0e9)
                            .set("material.density", 2440.0)
                            .set("material.fracture_energy", 135.0)
                            .set("discretization.spacing", 0.001)
                            .set("discretization.horizon_factor", 3.0)
                            .set("discretization.body.box.min", {0.0, 0.0, 0.0})
                            .set("discretization.body.box.max", {0.008, 0.008, 0.008})
                            .set("solver.time_step", 5.0e-8)
                            .set("solver.steps", 10)
                            .build("block"));
  NodeSet& ns = m.nodes;
  const double zc = 0.004;
  auto crosses = [&](std::size_t i, std::size_t j) {
    return (ns.x[2][i] - zc) * (ns.x[2][j] - zc) < 0;
  };
  for (std::size_t i = 0; i < ns.size(); ++i)
    for (std::uint64_t k = m.bonds.begin(i); k < m.bonds.end(i); ++k)
      if (crosses(i, m.bonds.neighbor[k])) m.bonds.beta[k] = -std::abs(m.bonds.beta[k]);
  AdaptSpec spec;
  spec.enabled = true;
  refine_nodes(m, all_active(m), spec);
  std::size_t across = 0, intact = 0;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    for (std::uint64_t k = m.bonds.begin(i); k < m.bonds.end(i); ++k) {
      if (!crosses(i, m.bonds.neighbor[k])) continue;
      ++across;
      intact += BondFamilies::intact(m.bonds.beta[k]);
    }
  }
  ASSERT_GT(across, 1000u);
  RecordProperty("intact_fraction_across", std::to_string(double(intact) / double(across)));
  EXPECT_LT(static_cast<double>(intact), 0.02 * static_cast<double>(across));
}

TEST(Adapt, InterfaceHorizonLowersTheLocalEnergyLossOfAWaveCrossingAPatch) {
  // Thesis 4.2, Table 4.3: a Gaussian wave crosses a level-1 patch. Halving the horizon in the
  // patch (model B) loses potential energy at the patch nodes next to the interface; giving those
  // nodes m times their distance to the coarse grid (model C) lowers the largest local loss, the
  // change of total energy and the reflection (thesis: 71.7% -> 21.6%, 0.44% -> 0.05%,
  // 1.64% -> 0.44%; we measure 20.0% -> 17.0%, 0.086% -> 0.025%, 1.47% -> 1.15%). The uniform
  // coarse run keeps its energy to 0.01% (Velocity-Verlet, linear bonds).
  const std::vector<WavePatchRow> rows = wave_patch_rows();
  ASSERT_EQ(rows.size(), 4u);
  const WavePatchRow &uniform = rows[0], &b = rows[2], &c = rows[3];
  EXPECT_LT(uniform.energy_change, 0.01);
  EXPECT_LT(c.w_drop[0], b.w_drop[0]);
  EXPECT_LT(c.energy_change, b.energy_change);
  EXPECT_LT(c.reflection, b.reflection);
  for (const WavePatchRow& r : rows) EXPECT_LT(r.energy_change, 0.5) << r.name;
}

TEST(Adapt, InterfaceHorizonsAfterSuccessiveEventsEqualABruteForceRecompute) {
  // Each event updates the interface horizons only near its own changes. After four events in
  // different places (two of them to level 2 inside level 1, one next to an earlier zone), every
  // refined node must still have the horizon the rule gives when applied to the whole grid:
  // m times the distance to its nearest coarser node within two of its spacings, never less
  // than its level's horizon.
  Model m = build_model(plate().build("cracked plate"));
  AdaptSpec spec;
  spec.enabled = true;
  spec.max_level = 2;
  spec.interface_horizon = true;
  auto refine_near = [&](double x, double y, double r, int level) {
    std::vector<std::uint32_t> parents;
    const NodeSet& ns = m.nodes;
    for (std::uint32_t i = 0; i < ns.size(); ++i)
      if ((ns.flags[i] & kActive) && ns.level[i] == level - 1 && std::abs(ns.x[0][i] - x) < r &&
          std::abs(ns.x[1][i] - y) < r)
        parents.push_back(i);
    ASSERT_FALSE(parents.empty());
    refine_nodes(m, parents, spec);
  };
  refine_near(0.008, 0.008, 0.003, 1);
  refine_near(0.008, 0.008, 0.001, 2);
  refine_near(0.0135, 0.008, 0.0025, 1);  // next to the first zone: its interface moves
  refine_near(0.022, 0.010, 0.002, 1);
  refine_near(0.022, 0.010, 0.0008, 2);
  const NodeSet& ns = m.nodes;
  std::size_t enlarged = 0, refined = 0;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive) || ns.level[i] == 0) continue;
    ++refined;
    const double base = level_horizon(m, spec, ns.level[i]);
    double dmin = INFINITY;
    for (std::size_t j = 0; j < ns.size(); ++j) {
      if (!(ns.flags[j] & kActive) || !(ns.spacing[j] > 1.5 * ns.spacing[i])) continue;
      double d2 = 0;
      for (int d = 0; d < ns.dim; ++d) {
        const double t = ns.x[d][j] - ns.x[d][i];
        d2 += t * t;
      }
      const double reach = 2.0 * ns.spacing[i];
      if (d2 <= reach * reach) dmin = std::min(dmin, std::sqrt(d2));
    }
    const double want = std::isfinite(dmin) ? std::max(base, base / ns.spacing[i] * dmin) : base;
    // To round-off: mirror-image coarse nodes at the same distance give distances an ulp apart
    // (with or without FMA contraction), and the event may have taken the other one.
    EXPECT_NEAR(ns.horizon[i], want, 1e-12 * want) << "node " << i << " level " << int(ns.level[i]);
    enlarged += want > base;
  }
  // Not vacuous: many interface nodes carry an enlarged horizon, and interior ones do not.
  EXPECT_GT(enlarged, 20u);
  EXPECT_LT(enlarged, refined);
}

TEST(Adapt, ReanchoredChildrenKeepMomentumInAnUnbalancedField) {
  // As above, but nothing cancels: the faces move at different speeds (2 and -0.5 m/s across,
  // 0.5 and 0.1 along) and the parent block sits off the crack line, so children re-anchored
  // across the crack take a velocity their parents did not have. The uniform shift of the new
  // nodes must give back the event's momentum exactly (to round-off of sum m |v|).
  Model m = build_model(rotated_cracked_plate());
  NodeSet& ns = m.nodes;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    const bool up = ns.x[1][i] > 0;
    ns.u[1][i] = up ? 2e-6 : -0.5e-6;
    ns.v[1][i] = up ? 2.0 : -0.5;
    ns.v[0][i] = up ? 0.5 : 0.1;
    ns.sync_current(i);
  }
  std::vector<std::uint32_t> parents;
  for (std::uint32_t i = 0; i < ns.size(); ++i)
    if (ns.x[0][i] > -0.004 && ns.x[0][i] < 0.009 && ns.x[1][i] > -0.0015 && ns.x[1][i] < 0.004)
      parents.push_back(i);
  const auto before = momentum_and_kinetic(ns);
  AdaptSpec spec;
  spec.enabled = true;
  const RefineStats st = refine_nodes(m, parents, spec);
  EXPECT_GT(st.reanchored, 0u);
  const auto after = momentum_and_kinetic(ns);
  for (int d = 0; d < 2; ++d)
    EXPECT_LT(std::abs(after.momentum[d] - before.momentum[d]), 1e-12 * before.momentum_scale)
        << "component " << d;
}

namespace {

// A 20 mm glass plate (1 mm, m = 3) whose bonds break at the stretch 1e-3.
DeckBuilder brittle_plate() {
  DeckBuilder d;
  d.set("model.dimension", 2)
      .set("material.youngs_modulus", 72.0e9)
      .set("material.density", 2440.0)
      .set("material.critical_stretch", 1.0e-3)
      .set("discretization.spacing", 1.0e-3)
      .set("discretization.horizon_factor", 3.0)
      .set("discretization.body.box.min", {0.0, 0.0})
      .set("discretization.body.box.max", {0.02, 0.02});
  return d;
}

}  // namespace

// Cracks stay fine: a parent whose child lost a bond to the dynamics (not to a pre-crack) is not
// coarsenable, while its quiet neighbours are.
TEST(Adapt, AParentWhoseChildHasADynamicallyBrokenBondIsNotCoarsened) {
  Model m = build_model(
      brittle_plate()
          .set("adapt", level_one()
                            .set("energy_trigger", 0.5)
                            .set("coarsen", true)
                            .set("visibility", false)
                            .append("initial_refinement",
                                    DeckBuilder()
                                        .set("region", test::box({0.006, 0.006}, {0.014, 0.014}))
                                        .set("level", 1)))
          .set("solver.steps", 1)
          .build("refined plate"));
  NodeSet& ns = m.nodes;
  const auto before = coarsenable_parents(m);
  ASSERT_GT(before.size(), 4u);
  // Break one bond of a child of the first coarsenable parent, as a step would.
  std::uint32_t child = 0;
  for (std::uint32_t i = 0; i < ns.size(); ++i)
    if (ns.parent[i] == static_cast<std::int32_t>(before[0])) child = i;
  const std::uint64_t k = m.bonds.begin(child);
  m.bonds.beta[k] = -std::abs(m.bonds.beta[k]);
  ns.broken_weight[child] += ns.volume[m.bonds.neighbor[k]];
  const auto after = coarsenable_parents(m);
  EXPECT_EQ(after.size(), before.size() - 1);
  EXPECT_EQ(std::count(after.begin(), after.end(), before[0]), 0);
}

#include "adapt/triggers.hpp"
#include "core/binary_archive.hpp"

// W_max of the energy trigger is taken over the nodes that can refine: a clamped or driven edge
// (which never refines) with a large boundary-layer energy must not switch the trigger off.
TEST(Adapt, EnergyTriggerIgnoresTheEnergyOfDrivenNodes) {
  const Deck dk = brittle_plate()
                      .append("boundary_conditions",
                              DeckBuilder()
                                  .set("name", "clamp")
                                  .set("region", test::box({0.0, 0.0}, {0.002, 0.02}))
                                  .set("velocity", test::Components{"0", "0"}))
                      .set("adapt", level_one().set("energy_trigger", 0.5))
                      .set("solver.steps", 1)
                      .build("clamped plate");
  const Model m = build_model(dk);
  const NodeSet& ns = m.nodes;
  std::vector<double> W(ns.size(), 0.1);
  std::uint32_t hot = 0;
  for (std::uint32_t i = 0; i < ns.size(); ++i) {
    if (ns.flags[i] & kBoundary) W[i] = 100.0;
    if (std::abs(ns.x[0][i] - 0.0105) < 1e-9 && std::abs(ns.x[1][i] - 0.0105) < 1e-9) hot = i;
  }
  W[hot] = 1.0;
  const std::vector<std::uint32_t> ids = energy_trigger(m, W, 0.5, refinable_nodes(m, dk.adapt));
  ASSERT_EQ(ids.size(), 1u);
  EXPECT_EQ(ids[0], hot);
}

// A deck that gives the critical stretch instead of G0 keeps the fracture energy that s0 implies
// at the base horizon: s0 ~ delta^(-1/2), so delta-scaled children of level l take s0 2^(l/2);
// m-scaled ones (the horizon kept) keep s0.
TEST(Adapt, ChildrenOfAGivenCriticalStretchKeepItsFractureEnergy) {
  for (const char* scaling : {"delta", "m"}) {
    SCOPED_TRACE(scaling);
    const Model m = build_model(
        brittle_plate()
            .set("adapt.max_level", 2)
            .set("adapt.scaling", scaling)
            .append("adapt.initial_refinement",
                    DeckBuilder()
                        .set("region", test::box({0.008, 0.008}, {0.012, 0.012}))
                        .set("level", 2))
            .set("solver.steps", 1)
            .build("refined plate"));
    int seen[3] = {0, 0, 0};
    for (std::size_t i = 0; i < m.nodes.size(); ++i) {
      if (!(m.nodes.flags[i] & kActive)) continue;
      const int l = m.nodes.level[i];
      ++seen[l];
      const double want = std::string(scaling) == "delta" ? 1e-3 * std::pow(2.0, 0.5 * l) : 1e-3;
      EXPECT_NEAR(m.nodes.critical_stretch[i] / want, 1.0, 1e-12) << "level " << l;
    }
    EXPECT_GT(seen[1], 0);
    EXPECT_GT(seen[2], 0);
  }
}

#include "studies/wave_levels_2d.hpp"

// Thesis 4.2, delta-m level 2 (m = 3, 4, 5 on levels 0-2), dual-horizon pairing: the levels'
// quadrature bond stiffness differs (PA-PDLAMMPS: 0.869, 0.880, 0.935), so the interfaces
// reflect du = 0.57% of the wave; with micromodulus_calibration: lattice 0.12%. Bounds: the
// issue's du <= 0.2% calibrated, and at least 0.4% uncalibrated (the test fails if the
// calibration stops acting).
TEST(Adapt, LatticeCalibrationRemovesTheDeltaMLevelReflection) {
  EXPECT_GT(wave_levels_delta_m_reflection(2, true, false), 0.4);
  EXPECT_LT(wave_levels_delta_m_reflection(2, true, true), 0.2);
}

// The automatic profile refines, before the run, the pre-crack's front (not its mouth at the free
// edge) and the regions driven by a moving prescribed motion (not held supports, a zero velocity
// or a constant offset), each widened by one horizon of visibility; named triggers leave both off.
TEST(Adapt, TheProfileRefinesPreCrackFrontsAndDrivenPatchesAtSetUp) {
  auto deck = [](const DeckBuilder& adapt) {
    return test::glass_plate({0.0, 0.0}, {0.06, 0.03})
        .append("cracks", DeckBuilder().set("segment", std::vector<std::vector<double>>{
                                                           {0.0, 0.015}, {0.0121, 0.015}}))
        .append("boundary_conditions", DeckBuilder()
                                           .set("name", "driven")
                                           .set("region", test::box({0.05, 0.029}, {0.06, 0.03}))
                                           .set("velocity", test::Components{std::nullopt, "1.0"}))
        .append("boundary_conditions", DeckBuilder()
                                           .set("name", "held")
                                           .set("region", test::box({0.05, 0.0}, {0.06, 0.001}))
                                           .set("displacement", test::Components{"0", "0"}))
        .append("boundary_conditions", DeckBuilder()
                                           .set("name", "still")
                                           .set("region", test::box({0.0, 0.0}, {0.01, 0.001}))
                                           .set("velocity", test::Components{"0", "0"}))
        .append("boundary_conditions", DeckBuilder()
                                           .set("name", "offset")
                                           .set("region", test::box({0.0, 0.029}, {0.01, 0.03}))
                                           .set("displacement", test::Components{"1e-6", "0"}))
        .set("adapt", adapt)
        .set("solver.end_time", 1e-7)
        .build("set-up zones");
  };
  const double delta = 0.003;
  const Vec3 tip{0.0121, 0.015, 0}, mouth{0.0, 0.015, 0};
  const auto dist = [](const NodeSet& ns, std::size_t i, const Vec3& p) {
    return std::hypot(ns.x[0][i] - p[0], ns.x[1][i] - p[1]);
  };
  {
    const Model m = build_model(deck(DeckBuilder().set("max_level", 1)));
    const NodeSet& ns = m.nodes;
    std::size_t near_tip = 0, fine_near_tip = 0, driven = 0, fine_driven = 0;
    for (std::size_t i = 0; i < ns.size(); ++i) {
      if (!(ns.flags[i] & kActive)) continue;
      const bool fine = ns.level[i] == 1;
      if (dist(ns, i, tip) <= delta) ++near_tip, fine_near_tip += fine;
      if (ns.x[0][i] >= 0.05 && ns.x[1][i] >= 0.029) ++driven, fine_driven += fine;
      // Beyond a horizon and a cell of the front (the front's zone is its visibility ball, not
      // widened again) and two horizons and a cell of the driven strip (zone, visibility,
      // children's offsets) everything is coarse: the mouth, the held support, the zero velocity
      // and the constant offset included.
      const double h = 0.001;
      const bool far_from_driven =
          ns.x[0][i] < 0.05 - 2 * delta - h || ns.x[1][i] < 0.029 - 2 * delta - h;
      if ((dist(ns, i, tip) > delta + h && far_from_driven) || dist(ns, i, mouth) <= delta) {
        EXPECT_EQ(ns.level[i], 0) << "node at " << ns.x[0][i] << ", " << ns.x[1][i];
      }
    }
    EXPECT_GT(near_tip, 20u);
    EXPECT_EQ(fine_near_tip, near_tip);
    EXPECT_GT(driven, 10u);
    EXPECT_EQ(fine_driven, driven);
  }
  // Named triggers: the thesis' explicit form, nothing refined before the run; nor with a start
  // time. With adapt.region the zones stay inside it (the driven strip, not the front).
  const Model plain = build_model(deck(DeckBuilder().set("max_level", 1).set("stretch_trigger", 0.5)));
  for (std::size_t i = 0; i < plain.nodes.size(); ++i) EXPECT_EQ(plain.nodes.level[i], 0);
  const Model later = build_model(deck(DeckBuilder().set("max_level", 1).set("start_time", 1e-8)));
  for (std::size_t i = 0; i < later.nodes.size(); ++i) EXPECT_EQ(later.nodes.level[i], 0);
  const Model inside = build_model(
      deck(DeckBuilder().set("max_level", 1).set("region", test::box({0.04, 0.0}, {0.06, 0.03}))));
  std::size_t refined_inside = 0;
  for (std::size_t i = 0; i < inside.nodes.size(); ++i) {
    if (!(inside.nodes.flags[i] & kActive) || inside.nodes.level[i] == 0) continue;
    ++refined_inside;
    EXPECT_GE(inside.nodes.x[0][i], 0.04);
  }
  EXPECT_GT(refined_inside, 10u);
}

// Damage on the finest level refines the coarse nodes that would see it when the damage trigger
// works alone (thesis Algorithm A.2). With the stretch trigger, coarse nodes are refined by their
// own bonds' stretch: an unloaded coarse node beside a crack on the finest level stays coarse
// (by proximity, every crack drew a band a coarse horizon wide along its faces).
TEST(Adapt, FineDamageRefinesUnloadedCoarseNodesOnlyWithoutTheStretchTrigger) {
  for (const bool stretch : {false, true}) {
    SCOPED_TRACE(stretch ? "stretch and damage triggers" : "damage trigger alone");
    DeckBuilder adapt = level_one().set("damage_trigger", true).set("check_every", 1);
    if (stretch) adapt.set("stretch_trigger", 0.5);
    const Deck dk = test::glass_plate({0.0, 0.0}, {0.06, 0.03})
                        .set("adapt", adapt)
                        .append("adapt.initial_refinement",
                                DeckBuilder()
                                    .set("region", test::box({0.025, 0.01}, {0.035, 0.02}))
                                    .set("level", 1))
                        .set("solver.end_time", 1e-7)
                        .build("refined plate");
    Model m = build_model(dk);
    NodeSet& ns = m.nodes;
    // A fine node 3.5-4 mm from the nearest coarse one: its bonds (1.5 mm) reach fine nodes only,
    // and those neighbours lie within a coarse horizon (3 mm) of coarse nodes.
    std::uint32_t kicked = 0;
    double best = 1e9;
    for (std::size_t i = 0; i < ns.size(); ++i) {
      if (!(ns.flags[i] & kActive) || ns.level[i] != 1) continue;
      double nearest = 1e9;
      for (std::size_t j = 0; j < ns.size(); ++j)
        if ((ns.flags[j] & kActive) && ns.level[j] == 0)
          nearest = std::min(nearest, std::hypot(ns.x[0][i] - ns.x[0][j], ns.x[1][i] - ns.x[1][j]));
      if (std::abs(nearest - 0.00375) < best) best = std::abs(nearest - 0.00375), kicked = i;
    }
    ASSERT_LT(best, 0.00025);
    ns.v[1][kicked] = 500.0;  // 25 um in one step: every bond of the node breaks
    const std::size_t n0 = ns.size();
    VelocityVerlet vv(m, 5.0e-8);
    vv.initialize();
    Adaptor ad(m, vv, dk.adapt);
    ASSERT_TRUE(ad.step());
    std::size_t broken = 0;
    for (std::uint64_t k = m.bonds.begin(kicked); k < m.bonds.end(kicked); ++k)
      broken += !BondFamilies::intact(m.bonds.beta[k]);
    EXPECT_GT(broken, 10u);
    if (stretch)
      EXPECT_EQ(ns.size(), n0) << "an unloaded coarse node was refined";
    else
      EXPECT_GT(ns.size(), n0) << "the coarse nodes that see the damage were not refined";
  }
}

// Once a bond has broken, the stretch trigger refines within stretch_reach horizons of a cracked
// node only. A plate held at a uniform strain of 0.6 of the children's critical stretch (above the
// trigger's 0.5, below the coarse bonds' own s0 at 1/sqrt(2)) and one node kicked hard enough to
// break its bonds: with the reach the zone stays around the kick, without it the whole plate is
// refined.
TEST(Adapt, OnceCrackedTheStretchTriggerRefinesNearCracksOnly) {
  for (const double reach : {2.0, 0.0}) {
    SCOPED_TRACE(reach > 0 ? "stretch_reach 2" : "stretch_reach 0");
    const Deck dk = test::glass_plate({0.0, 0.0}, {0.06, 0.03})
                        .set("adapt", level_one()
                                          .set("stretch_trigger", 0.5)
                                          .set("damage_trigger", true)
                                          .set("stretch_reach", reach))
                        .set("solver.end_time", 1e-7)
                        .build("strained plate");
    Model m = build_model(dk);
    NodeSet& ns = m.nodes;
    const double s_child = ns.critical_stretch[0] * std::sqrt(2.0);
    const double eps[3][3] = {{0.6 * s_child, 0, 0}, {0, 0.6 * s_child, 0}, {0, 0, 0}};
    test::apply_homogeneous_strain(ns, eps);
    const Vec3 kick{0.0305, 0.0155, 0};
    std::uint32_t kicked = 0;
    for (std::size_t i = 0; i < ns.size(); ++i)
      if (std::hypot(ns.x[0][i] - kick[0], ns.x[1][i] - kick[1]) < 1e-6) kicked = static_cast<std::uint32_t>(i);
    ASSERT_LT(std::hypot(ns.x[0][kicked] - kick[0], ns.x[1][kicked] - kick[1]), 1e-6);
    ns.v[1][kicked] = 500.0;  // 25 um in one step: its bonds break
    VelocityVerlet vv(m, 5.0e-8);
    vv.initialize();
    Adaptor ad(m, vv, dk.adapt);
    ASSERT_TRUE(ad.step());
    std::size_t far = 0, far_refined = 0, cracked = 0;
    for (std::size_t i = 0; i < ns.size(); ++i) {
      if (!(ns.flags[i] & kActive)) continue;
      cracked += ns.broken_weight[i] > 0;
      // The kicked node's neighbours are cracked (their bond to it broke); beyond them the reach,
      // the visibility ball and a parent's cell with its children's offset.
      if (std::hypot(ns.x[0][i] - kick[0], ns.x[1][i] - kick[1]) > (1.0 + 2.0 + 1.0) * 0.003 + 0.0015) {
        ++far;
        far_refined += ns.level[i] > 0;
      }
    }
    EXPECT_GT(cracked, 10u);
    EXPECT_GT(far, 1000u);
    if (reach > 0)
      EXPECT_EQ(far_refined, 0u);
    else
      EXPECT_GT(far_refined, far / 2);
    if (reach == 0) continue;
    // A restart keeps the rule: the body at rest at the same strain again (no bond breaks in the
    // next step), stepped by an adaptor restored from this one's state and by a fresh one.
    ArchiveWriter w;
    ad.save_state(w);
    const std::string state = w.take();
    for (std::size_t i = 0; i < ns.size(); ++i)
      for (int d = 0; d < 3; ++d) ns.v[d][i] = 0.0;
    test::apply_homogeneous_strain(ns, eps);
    for (const bool restored : {true, false}) {
      SCOPED_TRACE(restored ? "restored" : "fresh");
      Model mk = m;
      VelocityVerlet vk(mk, 5.0e-8);
      vk.initialize();
      Adaptor ak(mk, vk, dk.adapt);
      if (restored) {
        ArchiveReader r(state, "adaptor state");
        ak.restore_state(r);
      }
      const double broken_before = std::accumulate(mk.nodes.broken_weight.begin(), mk.nodes.broken_weight.end(), 0.0);
      ASSERT_TRUE(ak.step());
      const double broken_after = std::accumulate(mk.nodes.broken_weight.begin(), mk.nodes.broken_weight.end(), 0.0);
      std::size_t refined_now = 0;
      for (std::size_t i = 0; i < mk.nodes.size(); ++i)
        refined_now += (mk.nodes.flags[i] & kActive) && mk.nodes.level[i] > 0;
      std::size_t refined_before = 0;
      for (std::size_t i = 0; i < ns.size(); ++i) refined_before += (ns.flags[i] & kActive) && ns.level[i] > 0;
      EXPECT_EQ(broken_after, broken_before) << "a bond broke in the second step";
      if (restored)
        EXPECT_EQ(refined_now, refined_before);
      else
        EXPECT_GT(refined_now, refined_before + 1000);
    }
  }
}

TEST(Adapt, RelaxUntilCrackRelaxesTheEventsBeforeTheFirstBrokenBondOnly) {
  // A plate held at 0.6 of its children's critical stretch (the stretch trigger at 0.5 refines
  // it in the first step), with a fine zone from the start around one node. Kicked, that node
  // breaks its fine bonds in the first step, before the trigger's event: with relax_until_crack
  // the event is not relaxed (the same state as without relax_sweeps, bit for bit); not kicked,
  // nothing broke and the event is relaxed (a state other than the unrelaxed one).
  const Vec3 kick{0.0305, 0.0155, 0};
  auto first_step = [&](int sweeps, bool until_crack, bool kicked) {
    DeckBuilder a = level_one()
                        .set("stretch_trigger", 0.5)
                        .set("damage_trigger", true)
                        .set("relax_sweeps", sweeps)
                        .append("initial_refinement",
                                DeckBuilder()
                                    .set("region", test::box({0.0265, 0.0115}, {0.0345, 0.0195}))
                                    .set("level", 1));
    if (until_crack) a.set("relax_until_crack", true);
    const Deck dk = test::glass_plate({0.0, 0.0}, {0.06, 0.03})
                        .set("adapt", a)
                        .set("solver.end_time", 1e-7)
                        .build("strained plate");
    Model m = build_model(dk);
    NodeSet& ns = m.nodes;
    double s0 = 0;  // the coarse grid's
    for (std::size_t i = 0; i < ns.size(); ++i)
      if (ns.level[i] == 0 && (ns.flags[i] & kActive)) s0 = ns.critical_stretch[i];
    const double s_child = s0 * std::sqrt(2.0);
    const double eps[3][3] = {{0.6 * s_child, 0, 0}, {0, 0.6 * s_child, 0}, {0, 0, 0}};
    test::apply_homogeneous_strain(ns, eps);
    if (kicked) {
      std::uint32_t k = 0;
      double best = INFINITY;
      for (std::size_t i = 0; i < ns.size(); ++i)
        if ((ns.flags[i] & kActive) && ns.level[i] == 1) {
          const double r = std::hypot(ns.x[0][i] - kick[0], ns.x[1][i] - kick[1]);
          if (r < best) best = r, k = static_cast<std::uint32_t>(i);
        }
      EXPECT_LT(best, 4e-4);  // a child of the zone
      ns.v[1][k] = 500.0;  // 25 um in one step: its bonds break
    }
    VelocityVerlet vv(m, 5.0e-8);
    vv.initialize();
    Adaptor ad(m, vv, dk.adapt);
    EXPECT_TRUE(ad.step());
    EXPECT_EQ(ad.events().size(), 1u);  // the stretch trigger's, after the step's breaks
    double broken = 0;
    for (std::size_t i = 0; i < ns.size(); ++i) broken += ns.broken_weight[i];
    EXPECT_EQ(broken > 0, kicked);
    return ns.u;
  };
  EXPECT_EQ(first_step(5, true, true), first_step(0, false, true));
  EXPECT_NE(first_step(5, false, true), first_step(0, false, true));
  EXPECT_NE(first_step(5, true, false), first_step(0, false, false));
}

// A driven region that holds a whole family (a node all of whose bonds end inside it) carries
// the fine grid's force on the coarse grid and stays coarse; a small one is refined. (Driven
// disks of the compact-tension deck, coarse against fine force: radius 0.5 horizon 0.52-0.82,
// one horizon and more 0.89-1.09; docs/agrs.md.)
TEST(Adapt, TheProfileRefinesDrivenRegionsSmallAgainstAHorizonOnly) {
  const double delta = 0.003;
  const Vec3 big{0.015, 0.015, 0}, small{0.045, 0.015, 0};
  auto pin = [](const char* name, const Vec3& c, double r) {
    return DeckBuilder()
        .set("name", name)
        .set("region", DeckBuilder().set("disk.center", {c[0], c[1]}).set("disk.radius", r))
        .set("velocity", test::Components{"0", "1.0"});
  };
  const Model m = build_model(test::glass_plate({0.0, 0.0}, {0.06, 0.03})
                                  .append("boundary_conditions", pin("big", big, 2 * delta))
                                  .append("boundary_conditions", pin("small", small, 0.5 * delta))
                                  .set("adapt.max_level", 1)
                                  .set("solver.end_time", 1e-7)
                                  .build("driven disks"));
  const NodeSet& ns = m.nodes;
  std::size_t in_big = 0, in_small = 0, fine_small = 0;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    const double rb = std::hypot(ns.x[0][i] - big[0], ns.x[1][i] - big[1]);
    const double rs = std::hypot(ns.x[0][i] - small[0], ns.x[1][i] - small[1]);
    if (rb <= 2 * delta) {
      ++in_big;
      EXPECT_EQ(ns.level[i], 0) << "big disk node at r = " << rb;
    }
    if (rs <= 0.5 * delta) ++in_small, fine_small += ns.level[i] == 1;
  }
  EXPECT_GT(in_big, 100u);
  EXPECT_GT(in_small, 5u);
  EXPECT_EQ(fine_small, in_small);
}

// A quadrilateral pre-crack cut into a 3D beam from its bottom face: only the edge inside the body
// is a front (the edges outside the faces are not).
TEST(Adapt, CrackTipZonesOfAQuadrilateralFollowItsFrontInsideTheBody) {
  const Deck dk = DeckBuilder()
                      .set("model.dimension", 3)
                      .set("material.youngs_modulus", 30.0e9)
                      .set("material.density", 2400.0)
                      .set("material.fracture_energy", 5.0)
                      .set("discretization.spacing", 0.001)
                      .set("discretization.horizon_factor", 3.0)
                      .set("discretization.body.box.min", {0.0, 0.0, 0.0})
                      .set("discretization.body.box.max", {0.04, 0.01, 0.004})
                      .append("cracks", DeckBuilder().set(
                                            "quad", std::vector<std::vector<double>>{
                                                        {0.02, -0.001, -0.001}, {0.02, 0.003, -0.001},
                                                        {0.02, 0.003, 0.005}, {0.02, -0.001, 0.005}}))
                      .set("solver.end_time", 1e-7)
                      .build("notched beam");
  const Model m = build_model(dk);
  // The front edge, z from -1 to 5 mm, sampled every spacing: the points at z = 0 ... 4 mm have the
  // body beyond them; the other three edges lie outside the faces.
  const std::vector<InitialRefinement> zones = crack_tip_zones(m, 1);
  ASSERT_EQ(zones.size(), 5u);
  for (std::size_t k = 0; k < zones.size(); ++k) {
    const Shape& z = zones[k].region;
    EXPECT_EQ(z.kind, Shape::Kind::Sphere);
    EXPECT_DOUBLE_EQ(z.center[0], 0.02);
    EXPECT_DOUBLE_EQ(z.center[1], 0.003);
    EXPECT_NEAR(z.center[2], 0.001 * static_cast<double>(k), 1e-12);
    EXPECT_NEAR(z.radius, 0.003, 1e-12);  // one coarse horizon (m = 3)
  }
}
