#pragma once
// Crack-tip tracking (thesis 6.1) at the history steps: tip path and speed, initiation,
// branching; the summary's "crack" section and crack_speed.csv / .png.
#include "analysis/crack_tip.hpp"
#include "run/observer.hpp"

namespace periadapt {

class CrackTipObserver : public RunObserver {
 public:
  explicit CrackTipObserver(const RunView& view);
  void on_step(RunView& view, long step, bool closing) override;
  // It reads reference positions and damage, which every rank holds current.
  bool wants_state(const RunView&, long) const override { return false; }
  std::string progress_note() const override;
  void save(ArchiveWriter& w) override;
  void restore(ArchiveReader& r, RunView& view) override;
  void finish(RunView& view, RunResult& result) override;

  Vec3 last_tip() const { return last_tip_; }
  double current_speed() const { return tracker_.current_speed(); }

 private:
  CrackTipOptions tip_;
  CrackTipTracker tracker_;
  Vec3 last_tip_{NAN, NAN, NAN};
};

}  // namespace periadapt
