#pragma once
// VTU snapshots under one PVD, output.vtu_count of them evenly over the run (and one more when an
// interrupted run stops between them). A distributed run writes one piece per rank (its own
// rows) under a PVTU per snapshot.
#include <memory>
#include <set>

#include "io/vtu_writer.hpp"
#include "run/observer.hpp"

namespace periadapt {

class SnapshotObserver : public RunObserver {
 public:
  explicit SnapshotObserver(const RunView& view);
  bool wants_energy_density(long step) const override;
  void on_step(RunView& view, long step, bool closing) override;
  // A piece holds the rank's own rows, whose fields read its region only (their neighbours'
  // positions and displacements; LPS: two layers): no node need be brought up to date.
  bool wants_state(const RunView&, long) const override { return false; }
  bool own_rows_suffice() const override { return true; }
  void save(ArchiveWriter& w) override;
  void restore(ArchiveReader& r, RunView& view) override;
  void finish(RunView& view, RunResult& result) override;

 private:
  bool pieces_;  // distributed run: one VTU piece per rank under a PVTU
  std::set<long> steps_;
  std::unique_ptr<VtuSeries> vtu_;
};

}  // namespace periadapt
