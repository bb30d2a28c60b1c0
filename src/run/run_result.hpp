#pragma once
// What a run hands back to its caller: the outcome as typed fields (what `main` prints), the
// whole summary.json document, and the final model.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/geometry.hpp"
#include "model/model.hpp"

namespace periadapt {

struct CrackReport {
  std::optional<double> first_advance_s, initiation_s, branching_s;
  double mean_speed = 0, max_speed = 0;  // m/s
};

struct DivergenceReport {
  std::size_t node = 0;
  long step = 0;
  double time = 0;
  Vec3 position{0, 0, 0};
  std::string reason;
};

struct RunResult {
  bool diverged = false;
  int interrupted = 0;  // the signal that stopped the run (SIGINT, SIGTERM), 0 if none
  long steps_done = 0;  // with `interrupted`: the last step taken
  long steps = 0;       // steps taken in all (a restart counts the ones before it)
  double wall_s = 0, bond_evals_per_s = 0;
  std::optional<std::size_t> multirate_slow_nodes;
  std::optional<DivergenceReport> divergence;
  // A refinement event left the time step above the refined rows' stable step: the run stopped
  // after that step, with its outputs finished.
  std::optional<std::string> unstable_time_step;
  std::optional<CrackReport> crack;
  std::string pvd_path, history_path;  // empty when nothing was written
  nlohmann::json summary;
  Model model;  // final state
};

}  // namespace periadapt
