// The explicit run's outputs are observers (run/observer.hpp): a caller's own observer sees every
// step once and every refinement event once, the step's energy density it asks for equals a
// fresh bond pass over the same state, and what it adds to the summary arrives in the result.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

#include "adapt/adaptor.hpp"
#include "analysis/energy.hpp"
#include "input/deck_builder.hpp"
#include "io/atomic_output.hpp"
#include "io/temporary_files.hpp"
#include "run/simulation.hpp"
#include "solver/velocity_verlet.hpp"

using namespace periadapt;

namespace {

// A pre-cracked plate pulled apart hard enough that the crack starts within the run, with the
// automatic AGRS profile: steps, events and damage for the observers to see.
Deck cracked_plate(int steps, int history_every) {
  auto box = [](double x0, double y0, double x1, double y1) {
    return DeckBuilder().set("box.min", {x0, y0}).set("box.max", {x1, y1});
  };
  return DeckBuilder()
      .set("model.dimension", 2)
      .set("model.plane", "stress")
      .set("material.youngs_modulus", 72.0e9)
      .set("material.density", 2440.0)
      .set("material.fracture_energy", 135.0)
      .set("discretization.spacing", 0.001)
      .set("discretization.horizon_factor", 3.0)
      .set("discretization.body", box(0, 0, 0.04, 0.02))
      .append("cracks", DeckBuilder().set("segment", std::vector<std::vector<double>>{{0, 0.01}, {0.015, 0.01}}))
      .append("loads", DeckBuilder()
                           .set("type", "traction")
                           .set("region", box(0, 0.019, 0.04, 0.02))
                           .set("value", {0.0, 60e6}))
      .append("loads", DeckBuilder()
                           .set("type", "traction")
                           .set("region", box(0, 0, 0.04, 0.001))
                           .set("value", {0.0, -60e6}))
      .set("adapt.max_level", 1)
      .set("solver.time_step", 5e-8)
      .set("solver.steps", steps)
      .set("output.history_every", history_every)
      .build("observer test plate");
}

struct Recorder : RunObserver {
  std::vector<long> steps;
  std::size_t events = 0;
  long energy_checks = 0;
  double worst_energy_error = 0;
  bool finished = false;
  bool wants_energy_density(long step) const override { return step % 3 == 0; }
  void on_step(RunView& view, long step, bool closing) override {
    ASSERT_FALSE(closing);
    steps.push_back(step);
    if (step % 3 != 0) return;
    // The density the solver kept from the step's force pass, against a bond pass now.
    const std::vector<double> served = view.energy_density();
    std::vector<double> fresh;
    strain_energy(view.model, fresh);
    ASSERT_EQ(served.size(), fresh.size());
    double peak = 0;
    for (double w : fresh) peak = std::max(peak, std::abs(w));
    for (std::size_t i = 0; i < fresh.size(); ++i)
      worst_energy_error = std::max(worst_energy_error, std::abs(served[i] - fresh[i]) / peak);
    ++energy_checks;
  }
  void on_event(RunView& view, const RefinementEvent& e) override {
    // Observers hear of events once the step is done. An event is stamped with the state it
    // refined: the step just taken, or, where bonds broke on a coarse node and the step was
    // undone, refined and redone, the step before it.
    const bool redone = e.trigger == "damage" && e.step + 1 == view.vv.step_count();
    EXPECT_TRUE(e.step == view.vv.step_count() || redone) << e.trigger << " at " << e.step;
    ++events;
  }
  void finish(RunView&, RunResult& r) override {
    finished = true;
    r.summary["recorder"] = {{"steps_seen", steps.size()}, {"events_seen", events}};
  }
};

}  // namespace

TEST(Observers, ACallersObserverSeesEveryStepEventAndTheStepsOwnEnergyDensity) {
  const int steps = 120;
  auto rec = std::make_shared<Recorder>();
  RunOptions ro;
  ro.write_files = false;
  ro.quiet = true;
  ro.observers.push_back(rec);
  const RunResult r = run_simulation(cracked_plate(steps, 7), ro);
  ASSERT_GT(r.summary["adapt"]["events"].get<std::size_t>(), 0u) << "the plate must refine";
  ASSERT_GT(r.summary["broken_bonds"].get<std::size_t>(), 0u) << "and crack";
  // Steps 0 ... N, each once, in order.
  ASSERT_EQ(rec->steps.size(), static_cast<std::size_t>(steps + 1));
  for (long s = 0; s <= steps; ++s) EXPECT_EQ(rec->steps[s], s);
  EXPECT_EQ(rec->events, r.summary["adapt"]["events"].get<std::size_t>());
  EXPECT_TRUE(rec->finished);
  EXPECT_EQ(r.summary["recorder"]["steps_seen"].get<std::size_t>(), rec->steps.size());
  // The served densities are the force pass's own: the same sums over the same bonds, so equal
  // to round-off of the summation order (the rows are summed in the same order: 1e-12).
  EXPECT_EQ(rec->energy_checks, steps / 3 + 1);
  EXPECT_LT(rec->worst_energy_error, 1e-12);
  // The typed result carries what main prints.
  EXPECT_EQ(r.steps, steps);
  EXPECT_FALSE(r.divergence.has_value());
  EXPECT_TRUE(r.history_path.empty());  // nothing written
}

// A process ended by a second signal while writing FILE (FILE.tmp open) leaves FILE as it was and
// no FILE.tmp: the handler unlinks the temporaries the atomic writes have marked.
TEST(AtomicOutput, TheTemporaryOfAWriteInProgressIsRemovedBySecondSignalCleanup) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("periadapt_tmpfiles_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "checkpoint.bin").string();
  write_file_atomically(path, [](std::ostream& o) { o << "good"; });
  bool existed = false, gone = false;
  EXPECT_THROW(write_file_atomically(path,
                                     [&](std::ostream& o) {
                                       o << "half";
                                       o.flush();
                                       existed = fs::exists(path + ".tmp");
                                       remove_temporary_files_now();  // what the handler does
                                       gone = !fs::exists(path + ".tmp");
                                     }),
               OutputError);
  EXPECT_TRUE(existed);
  EXPECT_TRUE(gone);
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "good");
  // A finished write is no longer marked: a later file of that name is left alone.
  { std::ofstream(path + ".tmp") << "someone else's"; }
  remove_temporary_files_now();
  EXPECT_TRUE(fs::exists(path + ".tmp"));
  fs::remove_all(dir);
}
