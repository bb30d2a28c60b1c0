// Same deck, 1 and 2 threads: the same damage field and displacements (1e-12 relative), also with
// the refinement overlay, whose re-checks run inside the parallel breaking pass.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "run/simulation.hpp"
#include "test_helpers.hpp"

using namespace periadapt;

namespace {

// The crack-branching plate at 1 mm, 10 us: the crack starts, so breaking is exercised.
std::string branching_plate(const std::string& damage, const std::string& pairing = "source_horizon",
                            const std::string& solver_extra = "") {
  return "model: {dimension: 2, plane: stress}\n"
         "material: {youngs_modulus: 72.0e9, density: 2440, fracture_energy: 135}\n"
         "discretization: {spacing: 0.001, horizon_factor: 3, body: {box: {min: [0, 0], max: [0.1, 0.04]}}}\n"
         "cracks: [{segment: [[0, 0.02], [0.05, 0.02]]}]\n"
         "loads:\n"
         "  - {type: traction, region: {box: {min: [0, 0.039], max: [0.1, 0.04]}}, value: [0, 22.0e6]}\n"
         "  - {type: traction, region: {box: {min: [0, 0], max: [0.1, 0.001]}}, value: [0, -22.0e6]}\n"
         "solver: {time_step: 5.0e-8, end_time: 1.0e-5, bond_pairing: " + pairing + solver_extra + "}\n" +
         damage;
}

void expect_same_with_1_and_2_threads(const std::string& yaml) {
  const Deck dk = test::deck_from(yaml);
  RunOptions ro;
  ro.write_files = false;
  ro.quiet = true;
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  RunResult a = run_simulation(dk, ro);
  omp_set_num_threads(2);
  RunResult b = run_simulation(dk, ro);
  omp_set_num_threads(saved);
  ASSERT_GT(a.summary["broken_bonds"].get<std::size_t>(), 0u);
  ASSERT_EQ(a.model.nodes.size(), b.model.nodes.size());
  double umax = 0;
  for (std::size_t i = 0; i < a.model.nodes.size(); ++i)
    for (int d = 0; d < 2; ++d) umax = std::max(umax, std::abs(a.model.nodes.u[d][i]));
  for (std::size_t i = 0; i < a.model.nodes.size(); ++i) {
    EXPECT_NEAR(a.model.nodes.damage(i), b.model.nodes.damage(i), 1e-12);
    for (int d = 0; d < 2; ++d)
      EXPECT_NEAR(a.model.nodes.u[d][i], b.model.nodes.u[d][i], 1e-12 * umax);
  }
}

}  // namespace

TEST(Threads, ResultsDoNotDependOnThreadCount) {
  expect_same_with_1_and_2_threads(branching_plate(""));
}

TEST(Threads, DualHorizonResultsDoNotDependOnThreadCount) {
  // Adaptive (mixed horizons) with the dual-horizon pairing: reactions gathered in a second pass.
  expect_same_with_1_and_2_threads(branching_plate(
      "adapt: {max_level: 1, start_time: 4.0e-6, energy_trigger: 0.7, damage_trigger: true}\n",
      "dual_horizon"));
}

TEST(Threads, AdaptiveResultsDoNotDependOnThreadCount) {
  // AGRS with both triggers (refinement from 4 us, steps undone and redone, refinement ahead of
  // the running crack), with node generation B and A.
  for (const char* method : {"B", "A"}) {
    SCOPED_TRACE(method);
    expect_same_with_1_and_2_threads(branching_plate(
        std::string("adapt: {max_level: 1, method: ") + method +
        ", start_time: 4.0e-6, energy_trigger: 0.7, damage_trigger: true}\n"));
  }
}

TEST(Threads, MultiRateAdaptiveResultsDoNotDependOnThreadCount) {
  // AGRS with multi-rate stepping: the partial force passes, the idle rows' energy pass, the steps
  // undone in the middle of a slow node's cycle and, with ratio 3 (the coarse nodes on 150 ns),
  // the velocities synchronized around events.
  for (const char* rates : {", multirate: true", ", multirate: true, multirate_ratio: 3"}) {
    SCOPED_TRACE(rates);
    expect_same_with_1_and_2_threads(branching_plate(
        "adapt: {max_level: 1, start_time: 4.0e-6, energy_trigger: 0.7, damage_trigger: true}\n",
        "source_horizon", rates));
  }
}

TEST(Threads, OverlayResultsDoNotDependOnThreadCount) {
  for (const char* variant : {"interpolation: pddo", "interpolation: pim", "sampling: whole_bond"}) {
    SCOPED_TRACE(variant);
    expect_same_with_1_and_2_threads(
        branching_plate(std::string("damage: {overlay: {n: 2, ") + variant + "}}\n"));
  }
}
