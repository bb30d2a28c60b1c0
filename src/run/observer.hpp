#pragma once
// What an explicit run shows its outputs: a read-only view of the run at a step, and the hooks an
// output implements (history, snapshots, pictures, crack tip, refinement log, summary). A new
// output is one RunObserver in its own file, added to the list in run/simulation.cpp.
#include <chrono>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/binary_archive.hpp"
#include "input/deck.hpp"
#include "model/model.hpp"
#include "run/run_result.hpp"

namespace periadapt {

class VelocityVerlet;
class Adaptor;
struct RefinementEvent;

// What the run loop knows when it ends, for the summary.
struct RunTotals {
  std::string status = "completed";  // completed | diverged | unstable_time_step | interrupted
  bool restarted = false;
  long restarted_from_step = 0;
  int interrupted_by = 0;  // signal
  long steps_done = 0;
  double setup_s = 0, solver_s = 0, sampling_s = 0, wall_s = 0;
  double dt = 0, dt_stable = 0;
};

class RunView {
 public:
  using clock = std::chrono::steady_clock;
  RunView(const Deck& deck, const Model& model, const VelocityVerlet& vv, const Adaptor* adaptor,
          std::string dir, bool write_files, long total_steps, clock::time_point start);

  const Deck& deck;
  const Model& model;
  const VelocityVerlet& vv;
  const Adaptor* adaptor;  // null without AGRS
  const std::string dir;
  const bool write_files;
  const long total_steps;

  double elapsed_s() const;
  // The history schedule: every output.history_every steps and the last. `closing`: the run
  // stops after this step, and the sample the schedule did not give is taken now.
  bool history_due(long step, bool closing) const;
  // The current step's strain-energy density per node and total, computed once for all
  // observers: from the step's own force pass when an observer asked for it
  // (RunObserver::wants_energy_density), else by a bond pass. In a distributed run the first
  // call of a step is collective, and the densities may be valid for this rank's own rows only
  // (RunObserver::own_rows_suffice); the total is every rank's.
  const std::vector<double>& energy_density();
  double strain_energy();

  // Seconds spent writing snapshot and picture files (the observers that write them add theirs).
  double output_seconds = 0;
  RunTotals totals;  // filled in by the run loop before RunObserver::finish

 private:
  void sample_energy();
  clock::time_point start_;
  long energy_step_ = -1;
  std::vector<double> W_;
  double U_ = 0;
};

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  // A fresh run, before step 0 is observed: headers. (A restart calls restore instead.)
  virtual void on_start(RunView&) {}
  // Whether `step` needs the strain-energy density: the solver then keeps it from its force pass.
  virtual bool wants_energy_density(long /*step*/) const { return false; }
  // Whether the densities of each rank's own rows suffice (sums over the nodes, taken with
  // analysis/energy.hpp's partition argument; a snapshot's piece): a distributed step then need
  // not share them all.
  virtual bool own_rows_suffice() const { return false; }
  // Whether on_step(`step`) reads the nodes' state (distributed runs bring every node up to date
  // first; parallel/ghost_layer.hpp). Closing calls always get it.
  virtual bool wants_state(const RunView&, long /*step*/) const { return true; }
  // After step `step` (0: the initial state). `closing`: see RunView::history_due.
  virtual void on_step(RunView&, long /*step*/, bool /*closing*/) {}
  virtual void on_event(RunView&, const RefinementEvent&) {}
  // A few words for the progress bar, or nothing.
  virtual std::string progress_note() const { return {}; }
  // The observer's state in a checkpoint, and back.
  virtual void save(ArchiveWriter&) {}
  virtual void restore(ArchiveReader&, RunView&) {}
  // After the last step: its part of the result and of its summary.json, and its closing files.
  virtual void finish(RunView&, RunResult&) {}
};

}  // namespace periadapt
