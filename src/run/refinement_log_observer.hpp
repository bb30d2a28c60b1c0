#pragma once
// refinement.csv: one row per AGRS event (trigger, parents, children, momentum and kinetic energy
// across it, the stable step after it); the summary's "adapt" section.
#include "io/atomic_output.hpp"
#include "run/observer.hpp"

namespace periadapt {

class RefinementLogObserver : public RunObserver {
 public:
  explicit RefinementLogObserver(const RunView& view);
  void on_start(RunView& view) override;
  bool wants_state(const RunView&, long) const override { return false; }
  void on_event(RunView& view, const RefinementEvent& e) override;
  void save(ArchiveWriter& w) override;
  void restore(ArchiveReader& r, RunView& view) override;
  void finish(RunView& view, RunResult& result) override;

 private:
  StreamedOutput out_;
  double seconds_ = 0;  // wall time inside the events
};

}  // namespace periadapt
