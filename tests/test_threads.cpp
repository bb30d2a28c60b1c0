// Same deck, 1 and 2 threads: the same damage field and displacements (1e-12 relative), also with
// the refinement overlay, whose re-checks run inside the parallel breaking pass.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <string>
#include <utility>

#include "input/deck_builder.hpp"
#include "run/simulation.hpp"
#include "test_helpers.hpp"

using namespace periadapt;

namespace {

// The crack-branching plate at 1 mm, 10 us: the crack starts, so breaking is exercised.
DeckBuilder branching_plate(const std::string& pairing = "source_horizon", double crack_y = 0.02) {
  const std::vector<std::vector<double>> crack = {{0, crack_y}, {0.05, crack_y}};
  DeckBuilder d = test::glass_plate({0.0, 0.0}, {0.1, 0.04});
  d
      .append("cracks", DeckBuilder().set("segment", crack))
      .append("loads", DeckBuilder()
                           .set("type", "traction")
                           .set("region", test::box({0.0, 0.039}, {0.1, 0.04}))
                           .set("value", {0.0, 22.0e6}))
      .append("loads", DeckBuilder()
                           .set("type", "traction")
                           .set("region", test::box({0.0, 0.0}, {0.1, 0.001}))
                           .set("value", {0.0, -22.0e6}))
      .set("solver.time_step", 5.0e-8)
      .set("solver.end_time", 1.0e-5)
      .set("solver.bond_pairing", pairing);
  return d;
}

// AGRS from 4 us with both triggers.
DeckBuilder agrs() {
  DeckBuilder a;
  a.set("max_level", 1)
      .set("start_time", 4.0e-6)
      .set("energy_trigger", 0.7)
      .set("damage_trigger", true);
  return a;
}

void expect_same_with_1_and_2_threads(const DeckBuilder& deck) {
  const Deck dk = deck.build("branching plate");
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
  expect_same_with_1_and_2_threads(branching_plate());
}

TEST(Threads, DualHorizonResultsDoNotDependOnThreadCount) {
  // Adaptive (mixed horizons) with the dual-horizon pairing: reactions gathered in a second pass.
  expect_same_with_1_and_2_threads(branching_plate("dual_horizon").set("adapt", agrs()));
}

TEST(Threads, AdaptiveResultsDoNotDependOnThreadCount) {
  // AGRS with both triggers (refinement from 4 us, steps undone and redone, refinement ahead of
  // the running crack), with node generation B and A.
  for (const char* method : {"B", "A"}) {
    SCOPED_TRACE(method);
    // Method A puts level-1 nodes on cell edges: its crack runs a quarter spacing off one.
    const double crack_y = std::string(method) == "A" ? 0.01975 : 0.02;
    expect_same_with_1_and_2_threads(
        branching_plate("source_horizon", crack_y).set("adapt", agrs().set("method", method)));
  }
}

TEST(Threads, MultiRateAdaptiveResultsDoNotDependOnThreadCount) {
  // AGRS with multi-rate stepping: the partial force passes, the idle rows' energy pass, the steps
  // undone in the middle of a slow node's cycle and, with ratio 3 (the coarse nodes on 150 ns),
  // the velocities synchronized around events.
  for (const bool ratio_3 : {false, true}) {
    SCOPED_TRACE(ratio_3 ? "multirate: true, multirate_ratio: 3" : "multirate: true");
    DeckBuilder d = branching_plate();
    d.set("adapt", agrs()).set("solver.multirate", true);
    if (ratio_3) d.set("solver.multirate_ratio", 3);
    expect_same_with_1_and_2_threads(d);
  }
}

TEST(Threads, OverlayResultsDoNotDependOnThreadCount) {
  const std::pair<const char*, const char*> variants[] = {
      {"interpolation", "pddo"}, {"interpolation", "pim"}, {"sampling", "whole_bond"}};
  for (const auto& [key, value] : variants) {
    SCOPED_TRACE(std::string(key) + ": " + value);
    expect_same_with_1_and_2_threads(branching_plate()
                                         .set("damage.overlay.n", 2)
                                         .set(std::string("damage.overlay.") + key, value));
  }
}
