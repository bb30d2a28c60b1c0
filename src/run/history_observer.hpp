#pragma once
// history.csv: energies, damage, crack tip, node and bond counts, reactions and applied forces,
// named-region sums, at every output.history_every steps; the load-displacement picture at the
// end, and the summary's energies.
#include "io/atomic_output.hpp"
#include "run/observer.hpp"

namespace periadapt {

class CrackTipObserver;

class HistoryObserver : public RunObserver {
 public:
  // `tip`: where the crack-tip columns come from (null: the run tracks no tip).
  HistoryObserver(RunView& view, const CrackTipObserver* tip);
  void on_start(RunView& view) override;
  bool wants_energy_density(long step) const override;
  void on_step(RunView& view, long step, bool closing) override;
  // Its sums are each rank's own nodes' (exact, added over the ranks), and damage and bond
  // counts are shared every step: a distributed step need not bring every node up to date.
  bool wants_state(const RunView&, long) const override { return false; }
  bool own_rows_suffice() const override { return true; }
  void save(ArchiveWriter& w) override;
  void restore(ArchiveReader& r, RunView& view) override;
  void finish(RunView& view, RunResult& result) override;

 private:
  const CrackTipObserver* tip_;
  StreamedOutput out_;
  long every_, total_;
  double K_ = 0, U_ = 0, damage_sum_ = 0;
  // The external work, step and time of the last row, so that summary.json's energies are of
  // one state (after a divergence, the last good row's, not the diverged step's).
  double W_ext_ = 0, sample_time_ = 0;
  long sample_step_ = 0;
  std::size_t damaged_nodes_ = 0;
  bool rank_column_ = false;  // distributed runs: the partition's bond imbalance
};

}  // namespace periadapt
