#pragma once
// One explicit run from a validated deck: builds the model, integrates, observes, writes.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "input/deck.hpp"
#include "model/model.hpp"
#include "run/observer.hpp"
#include "run/run_result.hpp"

namespace periadapt {

struct RunOptions {
  std::optional<std::string> out_dir;  // overrides output.directory
  bool write_files = true;
  bool quiet = false;
  // Continue from this checkpoint (a checkpoint.bin, or the folder holding it).
  std::optional<std::string> restart;
  // Outputs of the caller's own (a study's probe, a test's recorder): they see every step and
  // event after the built-in observers, and add to the summary before it is written.
  std::vector<std::shared_ptr<RunObserver>> observers;
};


// Chosen time step and its stability bound; throws DeckError when the deck's time step exceeds
// the bound without solver.allow_unstable_time_step.
struct TimeStepChoice {
  double dt, dt_crit;
  std::size_t limiting_node;
  long steps;
  double level_ratio = 1.0;  // finest level's stable step / dt_crit (AGRS), 1 without
};
TimeStepChoice choose_time_step(const Deck& deck, const Model& model);

// mpirun: splits the model's force passes over the ranks (parallel/row_partition.hpp), with the
// deck's partition method and rebalance threshold.
void enable_distributed_forces(const Deck& deck, Model& model);

RunResult run_simulation(const Deck& deck, const RunOptions& opt);

}  // namespace periadapt
